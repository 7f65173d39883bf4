#include "strata/gpu/WindowContext.h"

// GLFW must not include a GL header of its own: epoxy provides GL.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

#include "DebugOutput.h"
#include "strata/core/Error.h"
#include "strata/gpu/Gl.h"

namespace strata::gpu {
namespace {

// GLFW reports errors through a callback; keep the last one for our message.
thread_local std::string tLastGlfwError;

void onGlfwError(int code, const char* description) {
    tLastGlfwError = description != nullptr ? description : ("error " + std::to_string(code));
}

// GLFW is initialised once and never terminated, like the EGL display in
// Context.cpp: glfwTerminate() unloads the GL driver, after which
// LeakSanitizer can no longer name (or suppress) the driver's process-lifetime
// allocations. The process's exit closes the X connection.
bool gInitialised = false;

}  // namespace

struct WindowContext::Impl {
    GLFWwindow* window = nullptr;
    DebugState debug;
};

WindowContext::WindowContext(const WindowOptions& options) : impl_(std::make_unique<Impl>()) {
    glfwSetErrorCallback(onGlfwError);
    if (!gInitialised) {
        if (glfwInit() != GLFW_TRUE) throw Error("GLFW: cannot initialise (" + tLastGlfwError + ")");
        gInitialised = true;
    }

    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);

    impl_->window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (impl_->window == nullptr) {
        throw Error("GLFW: no OpenGL 4.5 core window available (" + tLastGlfwError + ")");
    }
    glfwMakeContextCurrent(impl_->window);
    glfwSwapInterval(options.vsync ? 1 : 0);
    if (options.debug) enableDebugOutput(impl_->debug);
    setCurrentDebugState(&impl_->debug);
}

WindowContext::~WindowContext() {
    if (impl_->window == nullptr) return;
    if (glfwGetCurrentContext() == impl_->window) {
        glfwMakeContextCurrent(nullptr);
        if (currentDebugState() == &impl_->debug) setCurrentDebugState(nullptr);
    }
    glfwDestroyWindow(impl_->window);
}

void WindowContext::makeCurrent() {
    glfwMakeContextCurrent(impl_->window);
    setCurrentDebugState(&impl_->debug);
}

bool WindowContext::shouldClose() const { return glfwWindowShouldClose(impl_->window) != 0; }
void WindowContext::swapBuffers() { glfwSwapBuffers(impl_->window); }

int WindowContext::framebufferWidth() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(impl_->window, &w, &h);
    return w;
}

int WindowContext::framebufferHeight() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(impl_->window, &w, &h);
    return h;
}

bool WindowContext::debug() const noexcept { return impl_->debug.enabled; }
GLFWwindow* WindowContext::window() const noexcept { return impl_->window; }

}  // namespace strata::gpu
