#include "strata/gpu/Context.h"

// Keep X11's macros (None, Bool, Status) out: strata never talks to X through EGL.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <sys/mman.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "ContextInfo.h"
#include "DebugOutput.h"
#include "strata/core/Error.h"

namespace strata::gpu {
namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        const bool startOk = p == list || p[-1] == ' ';
        const bool endOk = p[n] == '\0' || p[n] == ' ';
        if (startOk && endOk) return true;
    }
    return false;
}

std::string eglErrorName(EGLint error) {
    switch (error) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error " + std::to_string(error);
    }
}

std::string profileName(const ContextOptions& options) {
    return options.compatibility ? "2.1 compatibility" : "4.5 core";
}

// Under an address-space limit (ulimit -v), a GL driver that runs out
// midway does not fail cleanly: Mesa's llvmpipe, measured with a cube at
// limits from 300 to 600 MB, printed its own warnings and no context (up to
// 400 MB), hung (420-430 MB) or aborted in LLVM's code generator (450 MB);
// from 460 MB it drew. strata-render had 243 MB of address space mapped
// when it asked for the context (its libraries and its worker's 64 MiB
// stack), so the driver needed over 207 MB more. Before the driver is
// asked, that room and a margin is reserved once and let go: where the
// limit leaves less, the context is refused as out of memory, which the
// programs report in their one line.
constexpr std::size_t kDriverAddressSpace = std::size_t(256) << 20;

void checkRoomForTheDriver() {
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
    void* room = mmap(nullptr, kDriverAddressSpace, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (room == MAP_FAILED) throw std::bad_alloc();
    munmap(room, kDriverAddressSpace);
}

}  // namespace

bool debugByDefault() {
    if (const char* env = std::getenv("STRATA_GL_DEBUG"); env != nullptr && *env != '\0')
        return std::strcmp(env, "0") != 0;
#ifdef NDEBUG
    return false;
#else
    return true;
#endif
}

struct Context::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string platform;
    DebugState debug;

    // Tries one display: initialise, create a 4.5 core context, make it
    // current, and check what the driver really gave. On failure appends why to
    // `why`, destroys what it made and returns false.
    bool tryDisplay(EGLDisplay candidate, const char* platformName, const ContextOptions& options,
                    std::vector<std::string>& why) {
        auto failed = [&](const std::string& what) {
            why.push_back(std::string(platformName) + ": " + what);
            return false;
        };
        if (candidate == EGL_NO_DISPLAY) return failed("no display");
        EGLint major = 0, minor = 0;
        if (eglInitialize(candidate, &major, &minor) != EGL_TRUE)
            return failed("eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
        // From here the display stays initialised, also on failure: displays are
        // never terminated. A platform hands every caller the same EGLDisplay, so
        // eglTerminate() would end other Contexts' contexts too; and Mesa unloads
        // its driver on eglTerminate(), after which LeakSanitizer can no longer
        // name (or suppress) the driver's process-lifetime allocations. The
        // driver goes with the process.

        const char* extensions = eglQueryString(candidate, EGL_EXTENSIONS);
        if (!hasExtension(extensions, "EGL_KHR_create_context") && (major < 1 || (major == 1 && minor < 5)))
            return failed("no EGL_KHR_create_context");
        if (!hasExtension(extensions, "EGL_KHR_surfaceless_context"))
            return failed("no EGL_KHR_surfaceless_context");
        if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return failed("no desktop OpenGL API");

        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
            const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (eglChooseConfig(candidate, want, &config, 1, &count) != EGL_TRUE || count < 1)
                return failed("no config for desktop OpenGL");
        }

        // 2.1 has no profiles; the mask says compatibility to a driver that
        // hands out a newer version than asked for.
        const bool compatibility = options.compatibility;
        const EGLint attributes[] = {
            EGL_CONTEXT_MAJOR_VERSION_KHR, compatibility ? 2 : 4,
            EGL_CONTEXT_MINOR_VERSION_KHR, compatibility ? 1 : 5,
            EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,
            compatibility ? EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT_KHR : EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
            EGL_CONTEXT_FLAGS_KHR, options.debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
            EGL_NONE};
        EGLContext created = eglCreateContext(candidate, config, EGL_NO_CONTEXT, attributes);
        if (created == EGL_NO_CONTEXT)
            return failed("eglCreateContext for " + profileName(options) + " failed (" + eglErrorName(eglGetError()) +
                          ")");
        if (eglMakeCurrent(candidate, EGL_NO_SURFACE, EGL_NO_SURFACE, created) != EGL_TRUE) {
            const EGLint error = eglGetError();
            eglDestroyContext(candidate, created);
            return failed("eglMakeCurrent failed (" + eglErrorName(error) + ")");
        }
        // A driver may hand back less than it was asked for; trust only what GL says.
        const bool gotIt = compatibility ? currentGlVersion() >= 21 && !currentGlIsCoreProfile()
                                         : currentGlVersion() >= 45 && currentGlIsCoreProfile();
        if (!gotIt) {
            const std::string version = currentGlString(GlString::Version);
            eglMakeCurrent(candidate, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(candidate, created);
            return failed("got OpenGL " + (version.empty() ? std::string("?") : version));
        }
        display = candidate;
        context = created;
        platform = platformName;
        return true;
    }
};

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
    checkRoomForTheDriver();
    std::vector<std::string> why;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    bool ok = false;

    // 1. Mesa's surfaceless platform: no display server, no GPU needed (llvmpipe).
    if (getPlatformDisplay != nullptr && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        ok = impl_->tryDisplay(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                               "surfaceless", options, why);
    } else {
        why.push_back("surfaceless: EGL_MESA_platform_surfaceless missing");
    }

    // 2. An EGL device (NVIDIA's driver offers no surfaceless platform).
    if (!ok && getPlatformDisplay != nullptr && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (queryDevices != nullptr && queryDevices(16, devices, &count) == EGL_TRUE) {
            for (EGLint i = 0; i < count && !ok; ++i)
                ok = impl_->tryDisplay(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr),
                                       "device", options, why);
        }
    }

    // 3. Whatever the default display is.
    if (!ok) ok = impl_->tryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default", options, why);

    if (!ok) {
        std::string reasons;
        for (const std::string& r : why) reasons += (reasons.empty() ? "" : "; ") + r;
        throw Error("EGL: no OpenGL " + profileName(options) + " context available (" + reasons + ")");
    }

    if (options.debug) enableDebugOutput(impl_->debug);
    setCurrentDebugState(&impl_->debug);
}

Context::~Context() {
    if (impl_->context == EGL_NO_CONTEXT) return;
    release();
    eglDestroyContext(impl_->display, impl_->context);  // the display stays (see tryDisplay)
}

void Context::makeCurrent() {
    if (eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context) != EGL_TRUE)
        throw Error("EGL: eglMakeCurrent failed (" + eglErrorName(eglGetError()) + ")");
    setCurrentDebugState(&impl_->debug);
}

void Context::release() {
    if (eglGetCurrentContext() != impl_->context) return;
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (currentDebugState() == &impl_->debug) setCurrentDebugState(nullptr);
}

bool Context::debug() const noexcept { return impl_->debug.enabled; }

std::string Context::vendor() const { return currentGlString(GlString::Vendor); }
std::string Context::renderer() const { return currentGlString(GlString::Renderer); }
std::string Context::version() const { return currentGlString(GlString::Version); }
std::string Context::platform() const { return impl_->platform; }

}  // namespace strata::gpu
