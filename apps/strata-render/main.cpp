// strata-render: render a CSG scene headless to PNG and EXR, exactly as
// docs/contract.md says. Thin: options, then parse -> geometry -> camera
// -> GL context -> renderer -> files. Everything is rendered before anything
// is written, and every output is staged before any is committed, so a
// failure leaves no output file behind. Several scenes are rendered in turn
// with one GL context and one renderer (its shaders compiled once); a scene
// that fails writes nothing and the others go on.

#include <chrono>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "Options.h"
#include "strata/scene/SceneLoad.h"
#include "StderrProgress.h"
#include "Worker.h"
#include "strata/camera/Camera.h"
#include "strata/camera/ViewBounds.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/core/Timing.h"
#include "strata/export/Export.h"
#include "strata/gpu/Context.h"
#include "strata/io/ImageWriter.h"
#include "strata/io/Stats.h"
#include "strata/model/Model.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/ColorScheme.h"
#include "strata/render/Renderer.h"
#include "strata/scene/Tree.h"

namespace {

using namespace strata;
using Clock = std::chrono::steady_clock;

// Fails before the (possibly long) render when an output's folder is missing;
// the writers check again when they write.
void checkOutputFolder(const std::string& path) {
    if (path.empty()) return;
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
        throw Error(SourceLocation{path, 0, 0}, "cannot write (no folder '" + parent.string() + "')");
}

// The GL context and the renderer, made at the first scene that needs them
// and kept for the next (the context made first, destroyed last).
struct Gpu {
    std::optional<gpu::Context> context;
    std::optional<render::Renderer> renderer;
};

// The frame: camera, GL context, renderer (or the CPU reference), and the
// images staged into `staged`.
// The model's meshes are let go once the renderer holds them, unless the
// CPU reference needs them (a million cubes: about 400 MB).
void renderImages(const apps::RenderOptions& options, const scene::Tree& tree, model::Model model, Gpu& gpu,
                  io::RunStats& stats, std::vector<io::StagedFile>& staged) {
    camera::Camera base;
    base.width = options.width;
    base.height = options.height;
    base.fovDegrees = options.fovDegrees;
    base.projection = options.projection;
    camera::Camera camera;
    try {
        camera = options.camera ? camera::cameraFromArguments(*options.camera, base)
                                : camera::defaultCamera(camera::viewBounds(tree, model), base);
    } catch (const Error& e) {
        // The camera's own checks speak of the option; say who is speaking.
        throw Error(std::string("strata-render: ") + e.what());
    }

    render::RenderSettings settings;
    settings.layers = options.layers;
    settings.colorScheme = options.colorScheme;
    settings.lighting = options.lighting;
    settings.outline = options.look.outline;
    // One frame: its layer texture is made for it alone, so smaller tiles
    // with more draws cost less than the memory they save (OpenSCAD's
    // example008 at 1024x768: 0.40 s and 150 MB instead of 0.57 s and 288 MB).
    settings.coverageTilingFrom = std::size_t(16) << 20;
    settings.coverageTilingDraws = 4.0;
    settings.readDepth = !options.depth.empty();
    settings.readNormal = !options.normal.empty();

    auto t = Clock::now();
    if (!gpu.context) gpu.context.emplace();
    stats.contextMs = msSince(t);
    stats.renderer = gpu.context->renderer();

    render::Frame frame;
    {
        if (!gpu.renderer) gpu.renderer.emplace();
        render::Renderer& renderer = *gpu.renderer;
        t = Clock::now();
        if (options.reference) {
            renderer.setScene(tree, model);
        } else {
            renderer.setScene(tree, std::move(model));
        }
        stats.uploadMs = msSince(t);
        if (options.reference) {
            // The CPU oracle finds the surfaces; the GPU only shades them, so
            // both paths' images differ only where their surfaces do.
            reference::ReferenceOptions referenceOptions;
            if (!options.quiet) referenceOptions.progress = reference::progressOnStderr();
            const reference::ReferenceImage image =
                reference::renderReference(tree, model, camera, referenceOptions);
            frame = renderer.shade(camera, settings,
                                   render::Renderer::ExternalResult{image.depth, image.normal, image.leaf, image.cut});
            frame.stats.notes.push_back("surfaces from the CPU reference ray caster (--reference)");
        } else {
            frame = renderer.render(camera, settings);
        }
    }
    stats.frame = frame.stats;

    t = Clock::now();
    if (!options.png.empty()) staged.push_back(io::stagePng(options.png, frame.width, frame.height, frame.rgba));
    if (!options.depth.empty())
        staged.push_back(io::stageDepthExr(options.depth, frame.width, frame.height, frame.depth));
    if (!options.normal.empty())
        staged.push_back(io::stageNormalExr(options.normal, frame.width, frame.height, frame.normal));
    stats.writeMs = msSince(t);
}

// One scene, every output staged, then committed.
int run(const apps::RenderOptions& options, Gpu& gpu) {
    const auto start = Clock::now();
    io::RunStats stats;
    stats.scene = options.scene;
    stats.width = options.width;
    stats.height = options.height;

    checkOutputFolder(options.png);
    checkOutputFolder(options.depth);
    checkOutputFolder(options.normal);
    checkOutputFolder(options.exportPath);

    auto t = Clock::now();
    scene::SceneFile file = scene::readSceneFile(options.scene, options.defines);
    const scene::Tree& tree = file.tree;
    stats.parseMs = msSince(t);
    // Warnings are printed once everything is written: a run that fails
    // says one line, its error.
    for (const Warning& w : tree.warnings) stats.warnings.push_back(w.message);
    stats.unsupported = tree.unsupported;
    stats.leaves = static_cast<int>(tree.leaves.size());
    stats.dimensions = tree.isFlat() ? 2 : 3;

    t = Clock::now();
    // Progress lines on stderr for a phase of long work (none with --quiet).
    auto phaseProgress = [&options](const char* phase) {
        return options.quiet ? nullptr : std::make_unique<apps::StderrProgress>("strata-render", phase);
    };
    model::Model model;
    {
        const std::unique_ptr<apps::StderrProgress> progress = phaseProgress("building the model");
        const ProgressScope scope(progress.get());
        model = model::buildModel(tree);
    }
    stats.geometryMs = msSince(t);
    for (const Warning& w : model.warnings) stats.warnings.push_back(w.message);
    for (const mesh::Mesh& mesh : model.leafMeshes) stats.triangles += mesh.triangles.size();

    // Every output is staged, then all are committed: a failure anywhere writes none.
    std::vector<io::StagedFile> staged;
    if (!options.exportPath.empty()) {
        t = Clock::now();
        const std::unique_ptr<apps::StderrProgress> progress = phaseProgress("exporting");
        const ProgressScope scope(progress.get());
        exporting::ExportSettings settings;
        settings.sampled = options.exportSampled;
        settings.resolution = options.exportResolution;
        settings.reference = options.reference;
        settings.faceColor = render::colorScheme(options.colorScheme).faceFront;
        exporting::StagedExport exported = exporting::stageExport(tree, model, options.exportPath, settings);
        stats.exportSampleMs = exported.sampleMs;
        stats.exportContourMs = exported.contourMs;
        for (const Warning& w : exported.warnings) stats.warnings.push_back(w.message);
        staged.push_back(std::move(exported.file));
        stats.exportMs = msSince(t);
    }
    // With --export alone nothing is rendered (and, for the exact export,
    // no GL context made).
    const bool images = !options.png.empty() || !options.depth.empty() || !options.normal.empty();
    if (images || options.exportPath.empty()) renderImages(options, tree, std::move(model), gpu, stats, staged);
    t = Clock::now();
    io::commitAll(staged);
    stats.writeMs += msSince(t);
    stats.totalMs = msSince(start);

    // A .scad's echo and warnings as OpenSCAD printed them, then strata's.
    if (!options.quiet) {
        for (const std::string& line : file.openscadOutput) std::cerr << line << '\n';
        for (const std::string& w : stats.warnings) std::cerr << w << '\n';
    }
    if (options.stats) std::cout << io::statsJson(stats) << std::endl;
    return 0;
}

// One scene; a failure is its one line on stderr, and no output of it.
bool runOne(const apps::RenderOptions& options, Gpu& gpu) {
    try {
        run(options, gpu);
        return true;
    } catch (const Error& e) {
        std::cerr << e.what() << '\n';
    } catch (const std::bad_alloc&) {
        std::cerr << options.scene << ": out of memory (the scene needs more memory than the process may use)\n";
    } catch (const std::exception& e) {
        // Not ours (a library's exception): still one line, still no output.
        std::cerr << "strata-render: " << e.what() << '\n';
    }
    return false;
}

// Every scene in turn; the exit status.
int renderAll(const apps::RenderOptions& options) {
    Gpu gpu;
    if (options.scenes.size() == 1) return runOne(apps::forScene(options, options.scene), gpu) ? 0 : 1;
    // Several scenes: each in turn; after a failure the renderer is made
    // anew, in case the failure left it half way through a frame.
    std::size_t failed = 0;
    for (const std::string& scene : options.scenes) {
        if (!runOne(apps::forScene(options, scene), gpu)) {
            ++failed;
            gpu.renderer.reset();
        }
    }
    if (failed > 0) {
        std::cerr << "strata-render: " << failed << " of " << options.scenes.size() << " scenes failed\n";
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    io::removeTemporariesOnSignals();
    const apps::ParseResult parsed = apps::parseOptions(argc, argv);
    if (parsed.exitNow) {
        (parsed.exitCode == 0 ? std::cout : std::cerr) << parsed.message << (parsed.message.ends_with('\n') ? "" : "\n");
        return parsed.exitCode;
    }
    // On a thread with a stack of a known size: building a model recurses
    // once a nested shape (Worker.h), and the main thread's stack is what
    // the environment gives it.
    try {
        return apps::startWorker([&] { return renderAll(parsed.options); }).get();
    } catch (const std::system_error& e) {
        std::cerr << "strata-render: " << e.what() << '\n';
        return 1;
    }
}
