#include "Viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "strata/render/Limits.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/io/ExportFormats.h"
#include "strata/gpu/Gl.h"
#include "strata/io/ImageWriter.h"
#include "strata/render/ColorScheme.h"
#include "strata/camera/ViewBounds.h"
#include "OverlayLines.h"

namespace strata::view {
namespace {

using Clock = std::chrono::steady_clock;

// How often the scene file is stat()ed for changes.
constexpr auto kReloadPoll = std::chrono::milliseconds(200);
// The file counts as deleted once this many polls in a row missed it: an
// editor's unlink-then-rename save is over well within one poll.
constexpr int kMissingPolls = 2;
// The axes' colour over the depth and normal views' black background: the
// light grey OpenSCAD's dark schemes (Starnight) use.
const glm::vec3 kAxesOnBlack(0xe5 / 255.0f);

}  // namespace

ImGuiSession::ImGuiSession(gpu::WindowContext& window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    // Popups (the colour schemes' list) opaque: the view must not show through.
    ImGui::GetStyle().Colors[ImGuiCol_PopupBg].w = 1.0f;
    // Our callbacks are installed first; the backend chains to them.
    ImGui_ImplGlfw_InitForOpenGL(window.window(), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
}

ImGuiSession::~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

namespace {

// Whether a Viewer's window exists, for wakeWindow on the loader's thread.
std::atomic<bool> windowOpen{false};

}  // namespace

void Viewer::wakeWindow() {
    if (windowOpen.load()) glfwPostEmptyEvent();
}

Viewer::Viewer(const ViewerOptions& options, LoadedScene initial, Loader* pending)
    : options_(options),
      window_(gpu::WindowOptions{options.width, options.height, "strata-view: " + options.scene, true, true, false}),
      loader_([] { glfwPostEmptyEvent(); }),
      watch_(options.scene),
      path_(options.scene),
      scene_(std::move(initial)) {
    settings_.layers = options.layers;
    settings_.colorScheme = options.colorScheme;
    settings_.lighting = options.lighting;
    settings_.outline = options.outline;
    rows_ = treeRows(scene_.tree);
    watchDependencies();
    windowOpen = true;
    if (pending != nullptr && pending->busy()) {
        loader_.takeOver(*pending);
        awaitingFirst_ = true;
    }
    installInput();
    imgui_ = std::make_unique<ImGuiSession>(window_);
    overlay_ = std::make_unique<Overlay>();
    resetView();
    for (const Warning& w : scene_.tree.warnings) std::cerr << w.message << '\n';
    console_.add(ConsoleLine::Kind::Info, "loaded " + path_);
    for (const std::string& line : scene_.openscadOutput) console_.addOpenscad(line);
    for (const Warning& w : scene_.tree.warnings) console_.add(ConsoleLine::Kind::Warning, w.message);
    if (!awaitingFirst_) rememberOpened();
}

void Viewer::rememberOpened() {
    const std::string why = recent_.add(path_);
    if (!why.empty()) console_.add(ConsoleLine::Kind::Warning, why);
}

void Viewer::openFile(const std::string& path) {
    if (path.empty()) return;
    console_.add(ConsoleLine::Kind::Info, "opening " + path);
    loader_.request(path);
}

Viewer::~Viewer() {
    windowOpen = false;
    imgui_.reset();  // before the window's context goes
    overlay_.reset();
}

camera::Camera Viewer::camera() const {
    camera::Camera base;
    base.width = target_.width() > 0 ? target_.width() : window_.framebufferWidth();
    base.height = target_.height() > 0 ? target_.height() : window_.framebufferHeight();
    if (fixedSize_) std::tie(base.width, base.height) = *fixedSize_;
    base.fovDegrees = fov_;
    base.projection = projection_;
    return orbit_.camera(base);
}

int Viewer::run(const std::vector<Command>& script) {
    std::size_t next = 0;
    while (!quit_) {
        const bool scripted = !options_.script.empty();
        if (scripted && next == script.size()) break;  // a script's end ends the session
        const bool idle = !viewDirty_ && !sceneDirty_ && !windowShot_;
        step(!scripted && idle);
        if (scripted && !quit_ && runCommand(script[next])) ++next;
    }
    return 0;
}

void Viewer::step(bool waitForEvents) {
    if (waitForEvents)
        glfwWaitEventsTimeout(loader_.busy() || exporter_.busy() ? 0.1
                                                                  : std::chrono::duration<double>(kReloadPoll).count());
    else
        glfwPollEvents();
    if (window_.shouldClose()) quit_ = true;
    pollReload();
    if (std::optional<LoadResult> result = loader_.poll()) applyLoad(std::move(*result));
    pollExport();
    if (sceneDirty_) uploadScene();
    if (fitTarget() && viewDirty_) renderView();
    drawWindow();
}

bool Viewer::fitTarget() {
    const int w = fixedSize_ ? fixedSize_->first : window_.framebufferWidth() - viewLeft();
    const int h = fixedSize_ ? fixedSize_->second : window_.framebufferHeight();
    if (w <= 0 || h <= 0) return false;
    if (w != target_.width() || h != target_.height()) {
        target_.resize(w, h);
        viewDirty_ = true;
    }
    return true;
}

void Viewer::pollReload() {
    const auto now = Clock::now();
    if (now - lastPoll_ < kReloadPoll) return;
    lastPoll_ = now;
    bool changed = watch_.changed();
    for (FileWatch& dependency : dependencyWatches_) changed = dependency.changed() || changed;
    if (changed) loader_.request(path_);
    const bool missing = watch_.missingPolls() >= kMissingPolls;
    if (missing == fileMissing_) return;
    fileMissing_ = missing;
    if (missing) {
        const std::string note = path_ + ": the file is gone; showing the last good version";
        std::cerr << note << '\n';
        console_.add(ConsoleLine::Kind::Warning, note);
    } else {
        console_.add(ConsoleLine::Kind::Info, path_ + ": the file is back");
    }
    updateTitle();
}

void Viewer::applyLoad(LoadResult result) {
    ++loadsFinished_;
    if (result.cancelled) {
        // Not an error in the file: the last good model stays, as does any error it had.
        std::cerr << result.error << '\n';
        console_.add(ConsoleLine::Kind::Info, result.error);
        return;
    }
    if (!result.scene) {
        // The last good model stays on screen; the panel, the view and the title say why the new one did not load.
        loadError_ = result.error;
        // A script's `open` reports its own failure, as the script's error.
        if (!scriptOpening_) std::cerr << result.error << '\n';
        console_.add(ConsoleLine::Kind::Error, result.error);
        updateTitle();
        return;
    }
    loadError_.clear();
    console_.add(ConsoleLine::Kind::Info, "loaded " + result.path + " in " +
                                              std::to_string(static_cast<long long>(result.milliseconds)) + " ms");
    for (const std::string& line : result.scene->openscadOutput) console_.addOpenscad(line);
    for (const Warning& w : result.scene->tree.warnings) console_.add(ConsoleLine::Kind::Warning, w.message);
    for (const Warning& w : result.scene->tree.warnings) std::cerr << w.message << '\n';
    const bool sameShape = result.scene->tree.nodes.size() == scene_.tree.nodes.size();
    scene_ = std::move(*result.scene);
    edgesStale_ = true;
    rows_ = treeRows(scene_.tree);
    // Node numbers only mean the same nodes while the tree keeps its shape.
    if (!sameShape) edits_ = {};
    if (result.path != path_ || awaitingFirst_) {
        // Another file, or the first: framed as a file opened first is (a
        // reload of the same file keeps the camera).
        path_ = result.path;
        watch_ = FileWatch(path_);
        resetView();
        awaitingFirst_ = false;
        rememberOpened();
    }
    watchDependencies();
    updateTitle();
    sceneDirty_ = true;
    loadOnItsWay_.emplace();
    loadOnItsWay_->requested = result.requested;
    loadOnItsWay_->finished = result.finished;
    loadOnItsWay_->loadMs = result.milliseconds;
}

void Viewer::watchDependencies() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path shown = fs::absolute(path_, ec).lexically_normal();
    std::vector<FileWatch> watches;
    for (const std::string& file : scene_.dependencies) {
        if (fs::path(file).lexically_normal() == shown) continue;  // watch_ has it
        // A file watched before keeps its stamp, so a save between the load
        // and now is still seen.
        auto kept = std::find_if(dependencyWatches_.begin(), dependencyWatches_.end(),
                                 [&](const FileWatch& w) { return w.path() == file; });
        watches.push_back(kept != dependencyWatches_.end() ? std::move(*kept) : FileWatch(file));
    }
    dependencyWatches_ = std::move(watches);
}

void Viewer::uploadScene() {
    sceneDirty_ = false;
    viewDirty_ = true;
    const auto start = Clock::now();
    try {
        renderer_.setScene(applyEdits(scene_.tree, edits_), scene_.model);
        renderError_.clear();
    } catch (const Error& e) {
        renderError_ = e.what();
    }
    if (loadOnItsWay_ && !loadOnItsWay_->uploaded) {
        loadOnItsWay_->uploadStarted = start;
        loadOnItsWay_->uploaded = Clock::now();
    }
}

void Viewer::renderView() {
    viewDirty_ = false;
    peelTiles_.clear();
    const camera::Camera cam = camera();
    try {
        if (debugView_ == DebugView::Shaded && !overlayOptions_.any()) {
            stats_ = renderer_.renderInto(target_.framebuffer(), 0, 0, cam, settings_);
        } else {
            // The overlay is tested against the frame's depth and leaves, so
            // they are read back; the debug views are drawn from them too.
            render::RenderSettings settings = settings_;
            settings.keepPeelLayers = debugView_ == DebugView::Peel;
            settings.keepBlockForms = debugView_ == DebugView::Forms;
            const render::Frame frame = renderer_.render(cam, settings);
            stats_ = frame.stats;
            DebugImage image;
            if (debugView_ == DebugView::Depth) image = depthImage(frame);
            if (debugView_ == DebugView::Normal) image = normalImage(frame);
            if (debugView_ == DebugView::Forms) image = formsImage(frame);
            if (debugView_ == DebugView::Peel) {
                PeelGrid grid = peelGrid(frame, target_.width(), target_.height());
                image = std::move(grid.image);
                peelTiles_ = std::move(grid.tiles);
            }
            const std::vector<std::uint8_t>& shown = debugView_ == DebugView::Shaded ? frame.rgba : image.rgba;
            target_.upload(shown);
            // The peel grid's small images are not the camera's view: no lines over them.
            if (overlayOptions_.any() && debugView_ != DebugView::Peel) {
                if (overlayOptions_.edges && edgesStale_) {
                    overlay_->setScene(scene_.model);
                    edgesStale_ = false;
                }
                OverlayOptions options = overlayOptions_;
                // The depth and normal views' background is black.
                const bool dark = debugView_ == DebugView::Depth || debugView_ == DebugView::Normal;
                options.axesColor = dark ? kAxesOnBlack : axesColor(settings_.colorScheme);
                overlay_->draw(target_.framebuffer(), cam, frame, shown, options);
            }
        }
        renderError_.clear();
    } catch (const Error& e) {
        renderError_ = e.what();
        std::cerr << e.what() << '\n';
    }
}

void Viewer::drawWindow() {
    const int fw = window_.framebufferWidth(), fh = window_.framebufferHeight();
    if (fw <= 0 || fh <= 0) return;  // minimised
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    const glm::vec4 bg = render::colorScheme(settings_.colorScheme).background;
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (target_.width() > 0) target_.blitToWindow(fh, viewLeft());

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (showPanel_) drawPanel();
    if (debugView_ == DebugView::Peel) drawPeelLabels();
    drawStaleBadge();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    // ImGui lays a new window out over its first frames: capture a later one.
    if (windowShot_ && --windowShotFrames_ <= 0) {
        io::writePng(*windowShot_, fw, fh, readWindow(fw, fh));
        windowShot_.reset();
        windowShotWritten_ = true;
    }
    window_.swapBuffers();
    // The first frame of a new model: its image is in the target, the window swapped.
    if (loadOnItsWay_ && loadOnItsWay_->uploaded && !sceneDirty_ && !viewDirty_ && target_.width() > 0) {
        glFinish();  // the frame is on screen, not only queued
        loadOnItsWay_->shown = Clock::now();
        lastShownLoad_ = loadOnItsWay_;
        loadOnItsWay_.reset();
    }
}

void Viewer::setLayers(int layers) {
    settings_.layers = std::clamp(layers, 0, render::kMaxLayers);
    viewDirty_ = true;
}

void Viewer::changeLayers(int delta) {
    // From auto, step from what auto used in the last frame.
    int current = settings_.layers;
    if (current == 0)
        for (int used : stats_.layersPerLeaf) current = std::max(current, used);
    setLayers(std::max(1, current + delta));
}

void Viewer::toggleProjection() {
    projection_ = projection_ == camera::Projection::Perspective ? camera::Projection::Orthographic
                                                                  : camera::Projection::Perspective;
    viewDirty_ = true;
}

void Viewer::setDebugView(DebugView view) {
    debugView_ = view;
    viewDirty_ = true;
}

void Viewer::setShowAxes(bool on) {
    overlayOptions_.axes = on;
    viewDirty_ = true;
}

void Viewer::setShowScale(bool on) {
    overlayOptions_.scale = on;
    viewDirty_ = true;
}

void Viewer::setShowEdges(bool on) {
    overlayOptions_.edges = on;
    viewDirty_ = true;
}

void Viewer::resetView() {
    orbit_ = fittedOrbit(camera::viewBounds(scene_.tree, scene_.model), camera());
    viewDirty_ = true;
}

void Viewer::viewAllNow() {
    orbit_ = viewAll(orbit_, camera::viewBounds(scene_.tree, scene_.model), camera());
    viewDirty_ = true;
}

void Viewer::recenterAt(int i, int j) {
    const camera::Camera cam = camera();
    if (i < 0 || j < 0 || i >= cam.width || j >= cam.height) return;
    // The depth AOV of a full read-back frame: costly, but only on a double click.
    // Called from GLFW's input callbacks: no exception may leave.
    float depth = INFINITY;
    try {
        const render::Frame frame = renderer_.render(cam, settings_);
        depth = frame.depth[static_cast<std::size_t>(j) * frame.width + i];
    } catch (const Error& e) {
        renderError_ = e.what();
    }
    if (!std::isfinite(depth)) return;  // the background: OpenSCAD ignores it too
    orbit_.recenter(pointAtDepth(cam, i, j, depth));
    viewDirty_ = true;
}

void Viewer::toggleHidden(int node) {
    if (!edits_.hidden.erase(node)) edits_.hidden.insert(node);
    sceneDirty_ = true;
}

void Viewer::toggleHighlight(int node) {
    if (!edits_.highlighted.erase(node)) edits_.highlighted.insert(node);
    sceneDirty_ = true;
}

void Viewer::saveScreenshot(const std::string& path) {
    // Drawn afresh at the view's present size, whatever the loop has drawn so
    // far: a screenshot must not depend on how many frames the window has had.
    if (sceneDirty_) uploadScene();
    if (!fitTarget()) throw Error("the view has no size to take a screenshot of");
    renderView();
    glFinish();
    io::writePng(path, target_.width(), target_.height(), target_.read());
}

void Viewer::saveChosenScreenshot() {
    if (screenshotPath_.empty()) {
        saveNumberedScreenshot();
        return;
    }
    try {
        if (!screenshotPath_.ends_with(".png")) throw Error("a screenshot is a .png file, not '" + screenshotPath_ + "'");
        saveScreenshot(screenshotPath_);
        message_ = "saved " + screenshotPath_;
    } catch (const Error& e) {
        message_ = e.what();
    }
}

void Viewer::saveNumberedScreenshot() {
    const std::string path = "strata-view-" + std::to_string(++screenshotCount_) + ".png";
    try {
        saveScreenshot(path);
        message_ = "saved " + path;
    } catch (const Error& e) {
        message_ = e.what();
    }
}

void Viewer::saveCsgExport(const std::string& path) {
    view::saveCsgExport(scene_, path_, path);
    message_ = "saved the CSG export to " + path;
    console_.add(ConsoleLine::Kind::Info, "saved the CSG export of " + path_ + " to " + path +
                                              ": the positions in messages and the tree's CSG lines are its lines");
}

void Viewer::saveChosenCsgExport() {
    const std::string path = csgExportPath_.empty() ? defaultCsgExportPath(path_) : csgExportPath_;
    try {
        saveCsgExport(path);
    } catch (const Error& e) {
        message_ = e.what();
        console_.add(ConsoleLine::Kind::Error, e.what());
    }
}

std::string Viewer::cameraLine() const { return cameraArgument(camera()); }

// "load_ms L handover_ms H upload_ms U first_frame_ms F total_ms T poll_ms P":
// parse and mesh on the worker; from the worker's end to the upload's start
// (waking the window's thread, replacing the old model); setScene; from the
// upload to the frame shown; from the request (the file watch noticing the
// save) to the frame shown: all of those, and the wait for the worker to
// start between; and how often the file is polled: a save waits up to that
// long to be noticed, outside every figure.
std::string Viewer::loadLine() const {
    if (!lastShownLoad_) return "no load";
    const LoadTimes& t = *lastShownLoad_;
    auto ms = [](Clock::duration d) { return std::to_string(std::chrono::duration<double, std::milli>(d).count()); };
    return "load_ms " + std::to_string(t.loadMs) + " handover_ms " + ms(*t.uploadStarted - t.finished) +
           " upload_ms " + ms(*t.uploaded - *t.uploadStarted) + " first_frame_ms " + ms(t.shown - *t.uploaded) +
           " total_ms " + ms(t.shown - t.requested) + " poll_ms " + ms(kReloadPoll);
}

void Viewer::copyCamera() {
    glfwSetClipboardString(window_.window(), cameraLine().c_str());
    message_ = "copied the --camera= argument";
}

// The panel is docked at the left; the view takes the rest of the window,
// so fitting and framing frame what can be seen.
int Viewer::viewLeft() const {
    if (!showPanel_) return 0;
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.window(), &ww, &wh);
    const double scale = window_.framebufferWidth() / double(std::max(ww, 1));
    return static_cast<int>(std::lround(std::min(panelWidth_, widestPanel()) * scale));
}

float Viewer::widestPanel() const {
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.window(), &ww, &wh);
    double widest = 0.5 * ww;
    if (fixedSize_) {
        const double unitsPerPixel = double(std::max(ww, 1)) / std::max(window_.framebufferWidth(), 1);
        widest = std::max(widest, ww - fixedSize_->first * unitsPerPixel);
    }
    return static_cast<float>(widest);
}

void Viewer::sizeWindowToFixedView() {
    // The panel's width is in window units, as the size of the window; the
    // view's is in pixels, as the framebuffer's (the same on Xvfb and most
    // screens; a HiDPI screen has more pixels than units).
    int ww = 1, wh = 1;
    glfwGetWindowSize(window_.window(), &ww, &wh);
    const double unitsPerPixel = double(std::max(ww, 1)) / std::max(window_.framebufferWidth(), 1);
    const int panel = showPanel_ ? static_cast<int>(std::lround(panelWidth_)) : 0;
    glfwSetWindowSize(window_.window(), panel + static_cast<int>(std::lround(fixedSize_->first * unitsPerPixel)),
                      static_cast<int>(std::lround(fixedSize_->second * unitsPerPixel)));
}

// "strata-view: FILE", and while the shown model is stale (its file no
// longer loads) a note that says so, visible with the panel hidden too.
std::string Viewer::title() const {
    std::string t = "strata-view: " + path_;
    if (fileMissing_)
        t += "  [deleted: showing the last good version]";
    else if (!loadError_.empty())
        t += "  [error: showing the last good version]";
    return t;
}

void Viewer::updateTitle() { glfwSetWindowTitle(window_.window(), title().c_str()); }

float Viewer::viewLeftInWindow() const {
    const float left = static_cast<float>(viewLeft()) / ImGui::GetIO().DisplayFramebufferScale.x;
    return std::max(left, showPanel_ ? panelWidth_ : 0.0f);
}

// The stale model's badge at the foot of the 3D view, beside the panel and
// wrapped to the view's width, drawn whether the panel shows or not.
void Viewer::drawStaleBadge() {
    if (loadError_.empty() && !fileMissing_) return;
    const ImGuiViewport* window = ImGui::GetMainViewport();
    const std::string text = fileMissing_ ? "the file is gone, showing the last good version: " + path_
                                          : "error, showing the last good version: " + loadError_;
    const float left = window->Pos.x + viewLeftInWindow();
    const float wrap = std::max(window->Pos.x + window->Size.x - left - 16.0f, 40.0f);
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->PushClipRect(ImVec2(left, window->Pos.y), ImVec2(window->Pos.x + window->Size.x, window->Pos.y + window->Size.y),
                       false);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
    const ImVec2 at(left + 8.0f, window->Pos.y + window->Size.y - size.y - 8.0f);
    draw->AddRectFilled(ImVec2(at.x - 4.0f, at.y - 2.0f), ImVec2(at.x + size.x + 4.0f, at.y + size.y + 2.0f),
                        IM_COL32(40, 0, 0, 200));
    draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, IM_COL32(255, 90, 90, 255), text.c_str(), nullptr, wrap);
    draw->PopClipRect();
}

// Beside the scene: model.csg -> model.stl.
std::string Viewer::defaultExportPath() const {
    std::filesystem::path p(path_);
    p.replace_extension(".stl");
    return p.string();
}

bool Viewer::startExport(const std::string& path) { return startExport(path, exportExact_); }

bool Viewer::startExport(const std::string& path, bool exact) {
    if (exporter_.busy()) {
        message_ = "an export is running";
        return false;
    }
    // A drawing (a 2D model's outlines) is exact only; the export itself
    // says which kind the model takes.
    const io::ExportFormat* format = io::exportFormatOf(path);
    if (format == nullptr || (!exact && format->kind != io::ExportKind::Mesh)) {
        message_ = Error(SourceLocation{path, 0, 0},
                         "cannot export to '" + lowerExtension(path) + "' (expected " +
                             (exact ? io::extensionList() : io::extensionList(io::ExportKind::Mesh)) + ")")
                       .what();
        return false;
    }
    exporter_.start(scene_, path, render::colorScheme(settings_.colorScheme).faceFront, exact, exportResolution_);
    message_ = "exporting " + path + "...";
    return true;
}

void Viewer::pollExport() {
    std::optional<ExportResult> done = exporter_.poll();
    if (!done) return;
    if (done->error.empty()) {
        message_ = "exported " + done->path + " (" + std::to_string(done->triangles) + " triangles, " +
                   std::to_string(static_cast<long long>(done->milliseconds)) + " ms)";
        console_.add(ConsoleLine::Kind::Info, message_);
        for (const std::string& w : done->warnings) {
            std::cerr << w << '\n';
            console_.add(ConsoleLine::Kind::Warning, w);
        }
    } else {
        message_ = done->error;
        std::cerr << done->error << '\n';
        console_.add(done->cancelled ? ConsoleLine::Kind::Info : ConsoleLine::Kind::Error, done->error);
    }
    lastExport_ = std::move(done);
}

}  // namespace strata::view
