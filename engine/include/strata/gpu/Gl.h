#pragma once
// The one way strata reaches OpenGL: libepoxy's loader, so every GL 4.5 entry
// point resolves against the current context (EGL headless or a GLFW window).
// Include this instead of any other GL header.

#include <epoxy/gl.h>

#include <string>
#include <string_view>

namespace strata::gpu {

// Attaches a debug label (KHR_debug, core in 4.3) to a GL object, so driver
// messages and frame debuggers name it. `identifier` is GL_BUFFER, GL_TEXTURE,
// GL_FRAMEBUFFER, GL_PROGRAM, GL_QUERY, GL_VERTEX_ARRAY, ...; labels longer than
// the driver's GL_MAX_LABEL_LENGTH are cut.
void setLabel(GLenum identifier, GLuint name, std::string_view label);

// GL's name for an enum that strata uses in messages ("GL_INVALID_OPERATION",
// "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT"), or "0x8CD6" for one it does not know.
std::string enumName(GLenum value);

}  // namespace strata::gpu
