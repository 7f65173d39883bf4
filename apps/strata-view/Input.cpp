// Mouse and keys, with OpenSCAD's conventions (docs/viewer.md, "Mouse and keys").
#include "Viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace strata::view {
namespace {

// Two left presses closer than this in time and space make a double click.
constexpr double kDoubleClickSeconds = 0.35;
constexpr double kDoubleClickPixels = 4.0;

Viewer& viewerOf(GLFWwindow* window) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

}  // namespace

void Viewer::installInput() {
    GLFWwindow* w = window_.window();
    glfwSetWindowUserPointer(w, this);
    // Set before ImGui's backend is initialised, which then chains to them.
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int b, int a, int m) { viewerOf(win).onMouseButton(b, a, m); });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) { viewerOf(win).onCursor(x, y); });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) { viewerOf(win).onScroll(dy); });
    glfwSetKeyCallback(w, [](GLFWwindow* win, int k, int, int a, int m) { viewerOf(win).onKey(k, a, m); });
}

void Viewer::onMouseButton(int button, int action, int mods) {
    double x = 0, y = 0;
    glfwGetCursorPos(window_.window(), &x, &y);
    if (action == GLFW_RELEASE) {
        if (button == drag_.button) drag_.button = -1;
        return;
    }
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureMouse) return;
    drag_ = Drag{button, x, y};
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    const double now = glfwGetTime();
    if (now - lastLeftPress_ < kDoubleClickSeconds && std::hypot(x - lastLeftX_, y - lastLeftY_) < kDoubleClickPixels) {
        // Window coordinates to framebuffer pixels (they differ on high-DPI screens).
        int ww = 1, wh = 1;
        glfwGetWindowSize(window_.window(), &ww, &wh);
        const double sx = window_.framebufferWidth() / double(std::max(ww, 1));
        const double sy = window_.framebufferHeight() / double(std::max(wh, 1));
        recenterAt(static_cast<int>(x * sx) - viewLeft(), static_cast<int>(y * sy));
        lastLeftPress_ = -1.0;
        drag_.button = -1;
        return;
    }
    lastLeftPress_ = now;
    lastLeftX_ = x;
    lastLeftY_ = y;
}

void Viewer::onCursor(double x, double y) {
    if (drag_.button < 0) return;
    const double dx = x - drag_.x, dy = y - drag_.y;
    drag_.x = x;
    drag_.y = y;
    const bool shift = glfwGetKey(window_.window(), GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                       glfwGetKey(window_.window(), GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    // The mouse moves in window units, the view is sized in framebuffer
    // pixels; OpenSCAD divides by the widget's size in the mouse's units.
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.window(), &ww, &wh);
    const double toWindow = double(std::max(ww, 1)) / std::max(window_.framebufferWidth(), 1);
    const int viewWidth = static_cast<int>(std::lround(target_.width() * toWindow));
    const int viewHeight = static_cast<int>(std::lround(target_.height() * toWindow));
    if (drag_.button == GLFW_MOUSE_BUTTON_LEFT)
        orbit_.orbit(dx, dy);
    else if (shift)
        orbit_.zoomDrag(dy);  // shift + right or middle drag
    else if (drag_.button == GLFW_MOUSE_BUTTON_MIDDLE)
        orbit_.moveAlongView(dy, viewHeight);
    else
        orbit_.pan(dx, dy, viewWidth, viewHeight);
    viewDirty_ = true;
}

void Viewer::onScroll(double dy) {
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureMouse) return;
    // Towards the cursor, in the view's framebuffer pixels.
    double x = 0, y = 0;
    glfwGetCursorPos(window_.window(), &x, &y);
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.window(), &ww, &wh);
    const double toPixels = window_.framebufferWidth() / double(std::max(ww, 1));
    orbit_.zoomAt(dy, x * toPixels - viewLeft(), y * toPixels, target_.width(), target_.height(), fov_);
    viewDirty_ = true;
}

void Viewer::onKey(int key, int action, int mods) {
    if (action == GLFW_RELEASE) return;
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureKeyboard) return;
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    // OpenSCAD's View menu: Ctrl+1, Ctrl+2, Ctrl+4..9 and Ctrl+0; the plain digits work too.
    switch (key) {
    case GLFW_KEY_1: setShowEdges(!overlayOptions_.edges); return;  // OpenSCAD: Ctrl+1, Show Edges
    case GLFW_KEY_2: setShowAxes(!overlayOptions_.axes); return;    // OpenSCAD: Ctrl+2, Show Axes
    case GLFW_KEY_4: orbit_.preset(Preset::Top); break;
    case GLFW_KEY_5: orbit_.preset(Preset::Bottom); break;
    case GLFW_KEY_6: orbit_.preset(Preset::Left); break;
    case GLFW_KEY_7: orbit_.preset(Preset::Right); break;
    case GLFW_KEY_8: orbit_.preset(Preset::Front); break;
    case GLFW_KEY_9: orbit_.preset(Preset::Back); break;
    case GLFW_KEY_0: orbit_.preset(Preset::Diagonal); break;
    case GLFW_KEY_V: viewAllNow(); return;              // OpenSCAD: Ctrl+Shift+V
    case GLFW_KEY_R: resetView(); return;
    case GLFW_KEY_O:
        if (ctrl) {  // OpenSCAD: Ctrl+O, Open
            focusOpen_ = true;
            showPanel_ = true;
        } else {
            toggleProjection();
        }
        return;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: changeLayers(+1); return;      // '+' is shift+'=' on most layouts
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: changeLayers(-1); return;
    case GLFW_KEY_A: setLayers(0); return;
    case GLFW_KEY_D: setDebugView(static_cast<DebugView>((static_cast<int>(debugView_) + 1) % kDebugViews)); return;
    case GLFW_KEY_H: showPanel_ = !showPanel_; return;
    case GLFW_KEY_C: copyCamera(); return;
    case GLFW_KEY_F5: loader_.request(path_); return;
    case GLFW_KEY_E:
        if (ctrl) startExport(exportPath_.empty() ? defaultExportPath() : exportPath_);
        return;
    case GLFW_KEY_S:
        if (ctrl) saveChosenScreenshot();
        return;
    case GLFW_KEY_F12: saveNumberedScreenshot(); return;
    case GLFW_KEY_Q:
        if (ctrl) quit_ = true;
        return;
    case GLFW_KEY_ESCAPE:
        // Stops what is running, a load first, then an export; never quits
        // (a load that has just finished would take the window with it):
        // Ctrl+Q quits, as in OpenSCAD.
        if (loader_.busy())
            loader_.cancel();
        else if (exporter_.busy())
            exporter_.cancel();
        return;
    default: return;
    }
    viewDirty_ = true;  // a preset
}

}  // namespace strata::view
