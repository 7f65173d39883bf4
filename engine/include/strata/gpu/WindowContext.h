#pragma once
// A GLFW window with an OpenGL 4.5 core context, for strata-view. Rendering
// code is shared with the headless Context: both give a current 4.5 context.
// Under Xvfb (CI) GLX gives 4.5 core on llvmpipe, so this works without a GPU.

#include <memory>
#include <string>

struct GLFWwindow;

namespace strata::gpu {

struct WindowOptions {
    int width = 1024;
    int height = 768;
    std::string title = "strata";
    bool visible = true;
    bool vsync = true;
    bool debug = false;  // synchronous KHR_debug output, as ContextOptions::debug
};

class WindowContext {
public:
    // Initialises GLFW (once per process; never terminated), opens the window and makes its
    // context current. Throws strata::Error("GLFW: ...") when there is no
    // display or no 4.5 core context.
    explicit WindowContext(const WindowOptions& options = {});
    ~WindowContext();
    WindowContext(const WindowContext&) = delete;
    WindowContext& operator=(const WindowContext&) = delete;

    void makeCurrent();
    bool shouldClose() const;
    void swapBuffers();
    // Size of the default framebuffer in pixels (may differ from the window's
    // size in screen units on high-DPI displays).
    int framebufferWidth() const;
    int framebufferHeight() const;
    bool debug() const noexcept;

    GLFWwindow* window() const noexcept;  // for input callbacks and ImGui

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strata::gpu
