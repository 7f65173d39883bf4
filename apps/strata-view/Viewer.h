#pragma once
// strata-view's window: the state of one viewing session and its event loop.
// The member functions are split by concern over several files:
//   Viewer.cpp    the loop, loading and reloading, rendering on demand, actions
//   Input.cpp     mouse and keys (OpenSCAD's conventions)
//   Panel.cpp     the Dear ImGui panel and the peel-grid labels
//   ScriptRun.cpp the --script commands

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "FileWatch.h"
#include "Console.h"
#include "Exporter.h"
#include "Loader.h"
#include "Orbit.h"
#include "Overlay.h"
#include "RecentFiles.h"
#include "Script.h"
#include "TreeEdit.h"
#include "ViewTarget.h"
#include "DebugImage.h"
#include "strata/remesh/Remesh.h"
#include "strata/gpu/WindowContext.h"
#include "strata/render/Renderer.h"

namespace strata::view {

enum class DebugView { Shaded, Depth, Normal, Peel, Forms };
inline constexpr int kDebugViews = static_cast<int>(DebugView::Forms) + 1;  // Forms is the last

struct ViewerOptions {
    std::string scene;
    std::string script;           // --script FILE; empty: interactive
    int width = 1024, height = 768;
    int layers = 0;               // 0: auto
    std::string colorScheme = "Cornfield";
    render::Lighting lighting = render::Lighting::Strata;  // --light
    bool outline = true;                                    // --no-outline clears it
};

// Dear ImGui's context and its GLFW / OpenGL 3 backends, for one window.
class ImGuiSession {
public:
    explicit ImGuiSession(gpu::WindowContext& window);
    ~ImGuiSession();
    ImGuiSession(const ImGuiSession&) = delete;
    ImGuiSession& operator=(const ImGuiSession&) = delete;
};

class Viewer {
public:
    // Opens the window on `initial`, the scene loaded from options.scene
    // (before the window, so that bad input fails before any window). With
    // a busy `pending` loader instead, its load of options.scene still
    // running, the window opens at once on an empty view, takes that load
    // over (its progress and cancel in the panel) and frames the model
    // when it arrives.
    Viewer(const ViewerOptions& options, LoadedScene initial, Loader* pending = nullptr);
    ~Viewer();
    // A loader's wake function for loads started before the window: wakes
    // the window's loop once there is one, and does nothing before.
    static void wakeWindow();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    // Until the window closes, or the script ends. Returns the exit status;
    // a failing script command throws its file:line:col strata::Error.
    int run(const std::vector<Command>& script);

private:
    struct Drag {
        int button = -1;  // GLFW_MOUSE_BUTTON_*; -1: none
        double x = 0, y = 0;
    };

    // Viewer.cpp
    void step(bool waitForEvents);
    void pollReload();
    void applyLoad(LoadResult result);
    void uploadScene();
    void renderView();
    // Sizes the view's target to the window (or the script's size); false while it has no area.
    bool fitTarget();
    void drawWindow();
    camera::Camera camera() const;
    void setLayers(int layers);
    void changeLayers(int delta);
    void toggleProjection();
    void setDebugView(DebugView view);
    // OpenSCAD's View menu toggles: Show Axes, Show Scale Markers, Show Edges.
    void setShowAxes(bool on);
    void setShowScale(bool on);
    void setShowEdges(bool on);
    void resetView();
    void viewAllNow();
    void recenterAt(int i, int j);
    void toggleHidden(int node);
    void toggleHighlight(int node);
    void saveScreenshot(const std::string& path);
    void saveNumberedScreenshot();
    void saveChosenScreenshot();  // to the panel's file name, or numbered when it is empty
    void copyCamera();
    // Writes the shown .scad's CSG export to `path` and says so in the
    // console; throws strata::Error (one line) when it cannot.
    void saveCsgExport(const std::string& path);
    void saveChosenCsgExport();  // to the panel's file name, or beside the .scad; errors go to the console
    // The panel's choice of export (exact or sampled, exportExact_), or the
    // one `exact` names. False, with the reason in message_, where none
    // started (another is running, or the name has no format for it).
    bool startExport(const std::string& path);
    bool startExport(const std::string& path, bool exact);
    void updateTitle();
    std::string title() const;
    void drawStaleBadge();
    // The 3D view's left edge in window units, right of the panel (also of
    // one dragged wider than the view's left edge): what is drawn over the
    // view stays right of it.
    float viewLeftInWindow() const;
    void pollExport();
    std::string defaultExportPath() const;
    std::string cameraLine() const;
    // print load: the last shown load's figures, or "no load".
    std::string loadLine() const;

    // Input.cpp
    void installInput();
    void onMouseButton(int button, int action, int mods);
    void onCursor(double x, double y);
    void onScroll(double dy);
    void onKey(int key, int action, int mods);

    // Panel.cpp
    void drawPanel();
    void drawTreePanel();
    // The "open" section: a path field with the folder's model files, and
    // the recent files; a click opens.
    void drawOpenPanel();
    void openFile(const std::string& path);
    // A file shown first, or in place of another: first in the recent files.
    void rememberOpened();
    // " (line N)", or " (CSG line N)" for a .scad's node: where the node is written; empty when unknown.
    std::string rowLineNote(int node) const;
    void drawPeelLabels();

    // ScriptRun.cpp: false while the command still waits (wait-reload, sleep).
    bool runCommand(const Command& command);

    ViewerOptions options_;
    // GL objects after the window (destroyed before it), ImGui's among them.
    gpu::WindowContext window_;
    std::unique_ptr<ImGuiSession> imgui_;
    render::Renderer renderer_;
    ViewTarget target_;
    std::unique_ptr<Overlay> overlay_;
    OverlayOptions overlayOptions_;
    bool edgesStale_ = true;         // the overlay's edges are not those of scene_.model
    Loader loader_;
    Exporter exporter_;
    std::string exportPath_;         // the panel's export file name
    std::string screenshotPath_;     // the panel's screenshot file name; empty: strata-view-N.png
    std::string csgExportPath_;      // the panel's file name for a .scad's CSG export; empty: beside the .scad
    std::string openPath_;           // the panel's "open" field: a file to open, or a folder to list
    bool focusOpen_ = false;         // Ctrl+O: unfold the "open" section and put the cursor in its field
    bool unfoldExport_ = false;      // a script's `panel export`: unfold the "export" section
    // Whether the panel's content kept inside its width on the last frame:
    // empty when it did, else the first section that passed its right edge.
    std::string panelOverflow_;
    std::string overflowThisFrame_;
    void noteOverflow(const char* section);
    // The folder the "open" section lists, read at most every two seconds.
    struct FolderEntry {
        std::string name;
        bool folder = false;
    };
    std::string listedFolder_;
    std::vector<FolderEntry> listed_;
    std::chrono::steady_clock::time_point listedAt_;
    RecentFiles recent_;
    bool exportExact_ = true;        // the panel exports CGAL's exact result, not the sampled one
    int exportResolution_ = remesh::kDefaultResolution;  // the sampled export's cells along the longest side
    Console console_;
    std::optional<ExportResult> lastExport_;  // the last finished export, for a waiting script
    FileWatch watch_;
    // The shown model's other files (LoadedScene::dependencies: a .scad's
    // use and include files and imports), as of its last good load: a
    // change to any reloads the model, as OpenSCAD does.
    std::vector<FileWatch> dependencyWatches_;
    bool awaitingFirst_ = false;     // the window opened before its first model: frame it when it comes
    void watchDependencies();
    std::chrono::steady_clock::time_point lastPoll_;

    std::string path_;
    LoadedScene scene_;              // the last good load
    std::vector<TreeRow> rows_;
    TreeEdits edits_;
    std::string loadError_;          // the last load's error; the previous scene stays on screen
    bool fileMissing_ = false;       // the shown file was deleted (FileWatch::missingPolls)
    std::string renderError_;
    int loadsFinished_ = 0;
    // A load's way to the screen, on the steady clock: asked for (the file
    // watch saw the change, or open / F5), parsed and meshed on the worker,
    // uploaded (Renderer::setScene), its first frame drawn and swapped.
    struct LoadTimes {
        std::chrono::steady_clock::time_point requested, finished;  // LoadResult's
        double loadMs = 0;  // parse and mesh (LoadResult::milliseconds)
        // setScene, with the tree edits applied: its start and end.
        std::optional<std::chrono::steady_clock::time_point> uploadStarted, uploaded;
        std::chrono::steady_clock::time_point shown;  // after glFinish
    };
    std::optional<LoadTimes> loadOnItsWay_;  // applied, its frame not yet shown
    std::optional<LoadTimes> lastShownLoad_; // the newest load whose frame was shown (print load)

    Orbit orbit_;
    camera::Projection projection_ = camera::Projection::Perspective;
    double fov_ = 22.5;
    render::RenderSettings settings_;
    DebugView debugView_ = DebugView::Shaded;
    std::vector<PeelTile> peelTiles_;
    render::FrameStats stats_;
    std::optional<std::pair<int, int>> fixedSize_;  // a script's `size`; else the window's
    bool showPanel_ = true;
    float panelWidth_ = 340.0f;      // the docked panel's width in window units (the user may drag its edge)
    std::optional<float> requestedPanelWidth_;  // a script's `panel WIDTH`, for the next frame
    int panelSettling_ = -1;         // frames a script's `panel WIDTH` still waits for the view to follow; -1: none
    int viewLeft() const;            // the 3D view's first framebuffer column: right of the panel
    // The widest the panel may be, in window units: half the window, or
    // under a script's `size` what the window holds beside the view.
    float widestPanel() const;
    // A script's `size`: the window as wide as the view and the panel beside it.
    void sizeWindowToFixedView();
    bool sceneDirty_ = true, viewDirty_ = true;
    bool quit_ = false;

    Drag drag_;
    double lastLeftPress_ = -1.0, lastLeftX_ = 0, lastLeftY_ = 0;
    std::string message_;            // the panel's last note (screenshot saved, camera copied)
    int screenshotCount_ = 0;

    // Script state
    std::string scriptPath_;
    int loadsAtWait_ = 0;
    bool scriptOpening_ = false;  // a script's `open` is waiting for its load
    std::optional<std::chrono::steady_clock::time_point> waitingSince_;
    std::optional<std::string> windowShot_;  // screenshot-window: written by drawWindow
    int windowShotFrames_ = 0;
    bool windowShotWritten_ = false;
};

}  // namespace strata::view
