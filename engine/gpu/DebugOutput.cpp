#include "DebugOutput.h"

#include <cstdio>

#include "strata/gpu/Gl.h"

namespace strata::gpu {
namespace {

thread_local DebugState* tCurrent = nullptr;

const char* sourceName(GLenum source) {
    switch (source) {
        case GL_DEBUG_SOURCE_API: return "api";
        case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
        case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
        case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
        case GL_DEBUG_SOURCE_APPLICATION: return "application";
        default: return "other";
    }
}

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity,
                               GLsizei length, const GLchar* message, const void* user) {
    auto* state = static_cast<DebugState*>(const_cast<void*>(user));
    const std::string text(message, length >= 0 ? static_cast<std::size_t>(length)
                                                 : std::char_traits<char>::length(message));
    if (type == GL_DEBUG_TYPE_ERROR) {
        if (state != nullptr && state->firstError.empty())
            state->firstError = std::string("GL error (") + sourceName(source) + "): " + text;
        return;
    }
    // Notifications are noise (buffer placement hints); warnings go to stderr.
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    std::fprintf(stderr, "strata: GL debug (%s, id %u): %s\n", sourceName(source), id, text.c_str());
}

}  // namespace

void enableDebugOutput(DebugState& state) {
    state.enabled = false;
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // the message arrives inside the failing call
    glDebugMessageCallback(onDebugMessage, &state);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    state.enabled = true;
}

void setCurrentDebugState(DebugState* state) { tCurrent = state; }
DebugState* currentDebugState() { return tCurrent; }

}  // namespace strata::gpu
