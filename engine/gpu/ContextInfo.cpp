#include "ContextInfo.h"

#include "strata/gpu/Gl.h"

namespace strata::gpu {

int currentGlVersion() {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    return major * 10 + minor;
}

bool currentGlIsCoreProfile() {
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    return (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
}

std::string currentGlString(GlString which) {
    const GLenum name = which == GlString::Vendor     ? GL_VENDOR
                        : which == GlString::Renderer ? GL_RENDERER
                                                      : GL_VERSION;
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s != nullptr ? s : "";
}

}  // namespace strata::gpu
