#pragma once
// A headless OpenGL 4.5 core context through EGL, for strata-render, the tests
// and the benchmark (and, on request, a 2.1 compatibility context, for the
// benchmark's OpenCSG comparator). No display, no window: render into your
// own Framebuffer.
//
// Platforms, tried in order: Mesa's surfaceless platform
// (EGL_PLATFORM_SURFACELESS_MESA; llvmpipe on a machine with no GPU), then an
// EGL device (EGL_EXT_platform_device; NVIDIA's driver), then the default
// display. The context has no config and no surface (EGL_KHR_no_config_context,
// EGL_KHR_surfaceless_context).
//
// The context is made current on the constructing thread and must outlive every
// GL object made while it is current (create it first, destroy it last).

#include <memory>
#include <string>

namespace strata::gpu {

struct DebugState;

// True in Debug builds (no NDEBUG) or when the environment sets STRATA_GL_DEBUG=1
// (STRATA_GL_DEBUG=0 turns it off in a Debug build).
bool debugByDefault();

struct ContextOptions {
    // Synchronous KHR_debug output; GL errors then fail loudly at checkErrors().
    bool debug = debugByDefault();
    // A GL 2.1 compatibility context (fixed-function drawing, as OpenCSG
    // needs) instead of 4.5 core, on the display a core context would get.
    bool compatibility = false;
};

class Context {
public:
    // Throws strata::Error("EGL: no OpenGL 4.5 core context available (<why>)")
    // when EGL or a 4.5 core context (with `compatibility`: "2.1
    // compatibility") is missing, and std::bad_alloc where an address-space
    // limit (ulimit -v) leaves the driver less than 256 MiB.
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Makes this context current on the calling thread (the constructor already did).
    void makeCurrent();
    // Leaves no context current on the calling thread, if this one is.
    void release();

    bool debug() const noexcept;
    std::string vendor() const;    // GL_VENDOR
    std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version() const;   // GL_VERSION
    std::string platform() const;  // which EGL platform gave the display: "surfaceless", "device", "default"

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strata::gpu
