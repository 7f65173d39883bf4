// The --script commands (Script.h), run between window frames so that a
// scripted session goes through the same code as mouse, keys and panel.
#include "Viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "strata/core/Error.h"
#include "strata/render/ColorScheme.h"

namespace strata::view {
namespace {

using Clock = std::chrono::steady_clock;

// wait-reload and wait-loading give up after this long: a test must fail, not hang.
constexpr auto kReloadTimeout = std::chrono::seconds(30);

// One poll of a wait not yet done: counted from its first poll, an error
// once it has taken kReloadTimeout, else a short wait for the next frame.
void keepWaiting(std::optional<Clock::time_point>& since, const char* timeoutMessage) {
    if (!since) since = Clock::now();
    if (Clock::now() - *since > kReloadTimeout) throw Error(timeoutMessage);
    glfwWaitEventsTimeout(0.02);
}
// screenshot-window: frames drawn before the capture, for ImGui's layout to settle.
constexpr int kWindowShotFrames = 3;

// Replaces `target` by a copy of `source` the way editors save: a new file beside it, renamed over it.
void replaceFile(const std::string& source, const std::string& target) {
    const std::string temporary = target + ".strata-view-tmp";
    std::error_code ec;
    std::filesystem::copy_file(source, temporary, std::filesystem::copy_options::overwrite_existing, ec);
    if (!ec) std::filesystem::rename(temporary, target, ec);
    if (ec) {
        std::filesystem::remove(temporary);
        throw Error("cannot replace '" + target + "' by '" + source + "' (" + ec.message() + ")");
    }
}

std::string statsLine(const render::FrameStats& s) {
    int used = 0;
    for (int l : s.layersPerLeaf) used = std::max(used, l);
    return "total_ms " + std::to_string(s.totalMs) + " peel_ms " + std::to_string(s.peelMs) + " evaluate_ms " +
           std::to_string(s.evaluateMs) + " normal_ms " + std::to_string(s.normalMs) + " plain_ms " + std::to_string(s.plainMs) + " shade_ms " +
           std::to_string(s.shadeMs) + " layers_used " + std::to_string(used) + " operands " +
           std::to_string(s.operands);
}

}  // namespace

bool Viewer::runCommand(const Command& c) {
    const std::string& script = options_.script;
    auto path = [&](std::size_t k) { return resolveScriptPath(script, c.words[k]); };
    try {
        switch (c.kind) {
        case CommandKind::Open:
            if (!waitingSince_) {
                loader_.request(path(0));
                loadsAtWait_ = loadsFinished_;
                waitingSince_ = Clock::now();
                scriptOpening_ = true;
            }
            [[fallthrough]];
        case CommandKind::WaitReload:
            // Done once a load has finished since the last wait and none is under way.
            if (!waitingSince_) waitingSince_ = Clock::now();
            if (loadsFinished_ > loadsAtWait_ && !loader_.busy()) {
                scriptOpening_ = false;
                if (c.kind == CommandKind::Open && !loadError_.empty()) throw Error(loadError_);
                loadsAtWait_ = loadsFinished_;
                waitingSince_.reset();
                return true;
            }
            keepWaiting(waitingSince_, "no reload within 30 s");
            return false;
        case CommandKind::WaitLoading:
            // Done once a load is under way (the watcher polls between frames).
            if (loader_.busy()) {
                waitingSince_.reset();
                return true;
            }
            keepWaiting(waitingSince_, "no load started within 30 s");
            return false;
        case CommandKind::Size:
            fixedSize_ = {static_cast<int>(c.numbers[0]), static_cast<int>(c.numbers[1])};
            sizeWindowToFixedView();
            viewDirty_ = true;
            return true;
        case CommandKind::Layers: setLayers(c.words[0] == "auto" ? 0 : static_cast<int>(c.numbers[0])); return true;
        case CommandKind::Camera:
            orbit_ = orbitFromCamera(camera::cameraFromArguments(c.numbers, camera()));
            viewDirty_ = true;
            return true;
        case CommandKind::Projection:
            projection_ = c.words[0] == "o" ? camera::Projection::Orthographic : camera::Projection::Perspective;
            viewDirty_ = true;
            return true;
        case CommandKind::Fov:
            fov_ = c.numbers[0];
            viewDirty_ = true;
            return true;
        case CommandKind::Orbit: orbit_.orbit(c.numbers[0], c.numbers[1]); break;
        case CommandKind::Pan: orbit_.pan(c.numbers[0], c.numbers[1], camera().width, camera().height); break;
        case CommandKind::MiddleDrag: orbit_.moveAlongView(c.numbers[1], camera().height); break;
        case CommandKind::ZoomDrag: orbit_.zoomDrag(c.numbers[0]); break;
        case CommandKind::Zoom:
            if (c.numbers.size() == 3)
                orbit_.zoomAt(c.numbers[0], c.numbers[1], c.numbers[2], camera().width, camera().height, fov_);
            else
                orbit_.zoom(c.numbers[0]);
            break;
        case CommandKind::Preset: orbit_.preset(presetFromName(c.words[0])); break;
        case CommandKind::ViewAll: viewAllNow(); return true;
        case CommandKind::DoubleClick:
            if (sceneDirty_) uploadScene();
            recenterAt(static_cast<int>(c.numbers[0]), static_cast<int>(c.numbers[1]));
            return true;
        case CommandKind::Toggle: toggleHidden(findNode(scene_.tree, c.words[0])); return true;
        case CommandKind::Highlight: toggleHighlight(findNode(scene_.tree, c.words[0])); return true;
        case CommandKind::Light:
            settings_.lighting = render::lightingNamed(c.words[0]);
            viewDirty_ = true;
            return true;
        case CommandKind::ColorScheme:
            settings_.colorScheme = render::colorScheme(c.words[0]).name;
            viewDirty_ = true;
            return true;
        case CommandKind::Debug: {
            const std::string& v = c.words[0];
            setDebugView(v == "depth"    ? DebugView::Depth
                         : v == "normal" ? DebugView::Normal
                         : v == "peel"   ? DebugView::Peel
                         : v == "forms"  ? DebugView::Forms
                                         : DebugView::Shaded);
            return true;
        }
        case CommandKind::Panel:
            if (!c.numbers.empty()) {
                // As a drag of the panel's edge: the panel takes the width (within
                // its bounds) on the next frame, and the view follows on the one after.
                if (panelSettling_ < 0) {
                    showPanel_ = true;
                    requestedPanelWidth_ = static_cast<float>(c.numbers[0]);
                    panelSettling_ = 2;
                }
                if (panelSettling_-- > 0) return false;
                viewDirty_ = true;
                return true;
            }
            showPanel_ = c.words[0] != "off";
            focusOpen_ = c.words[0] == "open";  // as Ctrl+O
            unfoldExport_ = c.words[0] == "export";
            if (fixedSize_) sizeWindowToFixedView();
            return true;
        case CommandKind::Show: {
            const bool on = c.words[1] == "on";
            if (c.words[0] == "axes") setShowAxes(on);
            if (c.words[0] == "scale") setShowScale(on);
            if (c.words[0] == "edges") setShowEdges(on);
            if (c.words[0] == "outline") {
                settings_.outline = on;
                viewDirty_ = true;
            }
            return true;
        }
        case CommandKind::Screenshot:
            saveScreenshot(path(0));
            if (!renderError_.empty()) throw Error(renderError_);
            return true;
        case CommandKind::ScreenshotWindow:
            // Asked here, written by drawWindow() a few frames later.
            if (windowShotWritten_) {
                windowShotWritten_ = false;
                return true;
            }
            if (!windowShot_) {
                windowShot_ = path(0);
                windowShotFrames_ = kWindowShotFrames;
            }
            return false;
        case CommandKind::Export:
        case CommandKind::ExportSampled:
            // Started once, then waited for; its error is the script's error.
            if (!waitingSince_) {
                lastExport_.reset();
                exportExact_ = c.kind == CommandKind::Export;  // as the panel's box would be for it
                if (!startExport(path(0))) throw Error(message_);
                waitingSince_ = Clock::now();
            }
            if (lastExport_ && !exporter_.busy()) {
                waitingSince_.reset();
                const std::string error = lastExport_->error;
                lastExport_.reset();
                if (!error.empty()) throw Error(error);
                return true;
            }
            glfwWaitEventsTimeout(0.02);
            return false;
        case CommandKind::SaveCsg: saveCsgExport(path(0)); return true;
        case CommandKind::Copy: replaceFile(path(0), path(1)); return true;
        case CommandKind::Remove: {
            std::error_code ec;
            if (!std::filesystem::remove(path(0), ec)) throw Error("cannot remove '" + path(0) + "'" + (ec ? " (" + ec.message() + ")" : ""));
            return true;
        }
        case CommandKind::Print: {
            const std::string& what = c.words[0];
            if (what == "camera") std::cout << cameraLine() << std::endl;
            if (what == "error") std::cout << (loadError_.empty() ? "no error" : loadError_) << std::endl;
            if (what == "stats") std::cout << statsLine(stats_) << std::endl;
            if (what == "console") std::cout << console_.text();
            if (what == "title") std::cout << title() << std::endl;
            if (what == "load") std::cout << loadLine() << std::endl;
            if (what == "panel") std::cout << (panelOverflow_.empty() ? "the panel's text fits its width" : panelOverflow_) << std::endl;
            if (what == "recent")
                for (const std::string& file : recent_.files()) std::cout << file << '\n';
            if (what == "tree")
                for (const TreeRow& row : rows_)
                    std::cout << std::string(static_cast<std::size_t>(row.depth) * 2, ' ') << row.node << ' '
                              << row.label << rowLineNote(row.node) << '\n';
            std::cout.flush();
            return true;
        }
        case CommandKind::Sleep:
            std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<long long>(c.numbers[0])));
            return true;
        case CommandKind::Key: {
            // As the window's key callback gets it (the panel has no text field focused).
            std::string_view name = c.words[0];
            const bool ctrl = name.starts_with("ctrl+");
            if (ctrl) name.remove_prefix(5);
            int key = GLFW_KEY_ESCAPE;
            if (name.size() == 1) key = name[0] >= 'a' ? GLFW_KEY_A + (name[0] - 'a') : GLFW_KEY_0 + (name[0] - '0');
            if (name == "f5") key = GLFW_KEY_F5;
            if (name == "f12") key = GLFW_KEY_F12;
            onKey(key, GLFW_PRESS, ctrl ? GLFW_MOD_CONTROL : 0);
            return true;
        }
        case CommandKind::Quit: quit_ = true; return true;
        }
    } catch (const Error& e) {
        throw c.error(e.what());
    }
    viewDirty_ = true;  // the camera moves
    return true;
}

}  // namespace strata::view
