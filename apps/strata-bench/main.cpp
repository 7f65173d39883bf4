// strata-bench: frame times of strata's renderer on seeded scenes built in
// code (Scenes.h), against the floor of drawing the same triangles once with
// a depth test (PlainDraw.h), in the same process and GL context, and
// against OpenCSG (OpenCsgRun.h) in a second, compatibility context of the
// same process where OpenCSG was built in (GLX with an X display, else EGL).
// Your own scene files (.csg, .scad through openscad, or one closed mesh)
// run the same way, from OpenSCAD's default view, with K their number of
// leaves.
// Run by hand (docs/benchmarks.md); never by CI.
//
//   strata-bench [--scenes cheese,stack] [--k 1,8,32] [--size 1024x768,512x512]
//                [--files model.csg,part.stl,gear.scad] [-D teeth=12] [--frames 10] [--warmup 2]
//                [--seed 1] [--json FILE] [--no-opencsg] [--opencsg-cap-ms 2000]
//                [--glibc-heap] [--no-groups] [--no-plain] [--light strata|openscad] [--no-outline]
//                [--opencsg-convexity openscad|measured]
//                [--opencsg-limit 100000] [--opencsg-context auto|glx|egl]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "CommandLine.h"
#include "HugePages.h"
#include "OpenCsgRun.h"
#include "OpenscadOptions.h"
#include "PlainDraw.h"
#include "strata/scene/SceneLoad.h"
#include "Scenes.h"
#include "strata/camera/Camera.h"
#include "strata/camera/ViewBounds.h"
#include "strata/core/Error.h"
#include "strata/core/Timing.h"
#include "strata/gpu/Check.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"
#include "strata/io/Json.h"
#include "strata/model/Model.h"
#include "strata/render/Limits.h"
#include "strata/render/Renderer.h"

namespace {

using namespace strata;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Size {
    int width = 0, height = 0;
};

// "1024x768" -> {1024, 768}; throws strata::Error on anything else.
Size parseSize(const std::string& text) {
    const std::size_t x = text.find_first_of("xX");
    try {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        std::size_t used = 0;
        const int w = std::stoi(text.substr(0, x), &used);
        if (used != x) throw std::invalid_argument("width");
        const std::string rest = text.substr(x + 1);
        const int h = std::stoi(rest, &used);
        if (used != rest.size()) throw std::invalid_argument("height");
        if (w < 1 || h < 1 || w > render::kMaxImageSide || h > render::kMaxImageSide) throw std::invalid_argument("range");
        return {w, h};
    } catch (const std::exception&) {
        throw Error("--size: expected WxH with 1 <= W, H <= " + std::to_string(render::kMaxImageSide) + ", got '" + text +
                    "'");
    }
}

struct Options {
    std::vector<std::string> scenes = bench::sceneNames();
    std::vector<int> ks{1, 8, 32, 64, 128, 256};
    std::vector<std::string> files;  // scene files, each once per size
    std::vector<std::string> defines;  // -D NAME=VALUE, for each .scad of files
    std::vector<std::string> sizes{"1024x768"};
    int frames = 10;
    int warmup = 2;
    unsigned seed = 1;
    std::string json;
    bool openCsg = true;
    double openCsgCapMs = 2000;
    std::string openCsgConvexity = "openscad";
    std::string openCsgContext = "auto";
    std::size_t openCsgLimit = bench::kOpenScadRenderingLimit;
    bool steadyHeap = true;
    bool groups = true;  // RenderSettings::groupOperands
    bool plainUnions = true;  // RenderSettings::plainUnions
    apps::LookOptions look;   // RenderSettings::lighting, ::outline
    render::Lighting lighting = render::Lighting::Strata;
};

// llvmpipe bins each frame's triangles into blocks it mallocs and frees
// again. glibc returns freed memory at the top of its heap to the kernel
// once more than a threshold is free, and adjusts that threshold to the
// largest block the process has freed so far, so whether each frame faults
// its binning memory in afresh depended on what the process had allocated
// before: the knot mesh's normal pass took 36 or 58 ms of CPU from one build
// to the next. Fixed thresholds give every renderer of the run (strata,
// plain, OpenCSG) the same, steady heap. Returns what the header says.
std::string steadyHeap(bool steady) {
#ifdef __GLIBC__
    if (steady) {
        mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest; fixed, not adjusted
        mallopt(M_TRIM_THRESHOLD, 256 << 20);
        return "heap: glibc's trim threshold fixed at 256 MiB, mmap threshold at 32 MiB";
    }
    return "heap: glibc's adaptive thresholds";
#else
    (void)steady;
    return "heap: the C library's defaults";
#endif
}

struct Result {
    std::string scene;
    int k = 0;
    Size size;
    std::size_t triangles = 0;
    int operands = 0;
    double setupMs = 0;                    // geometry + setScene
    double strataMs = 0, strataMinMs = 0;  // wall clock per frame, glFinish at its end included
    double strataPassTimedMs = 0;          // the same, with a glFinish after each pass (RenderSettings::passTimes)
    double peelMs = 0, evaluateMs = 0, normalMs = 0, plainFrameMs = 0, shadeMs = 0;  // FrameStats, medians
    bool plainFrame = false;               // FrameStats::plain: strata drew the union plainly
    std::size_t plainBesideLeaves = 0;     // FrameStats::plainBesideLeaves: leaves drawn plainly beside the CSG
    double plainMs = 0, plainMinMs = 0;
    std::size_t plainBytes = 0;            // the floor's vertex buffer and framebuffer
    std::size_t textureBytes = 0;
    int layersTotal = 0, layersMax = 0;
    std::size_t coveredPixels = 0;
    int tiles = 1;
    std::vector<std::string> notes;
    bench::OpenCsgResult openCsg;
    std::string error;                     // non-empty: this case failed
};

// OpenCSG for the whole run: the comparator, or why there is none.
struct OpenCsgSide {
    std::unique_ptr<bench::OpenCsgComparator> comparator;
    std::string unavailable;
    bench::OpenCsgCaps caps;
};

std::vector<std::uint8_t> coverageOf(const render::Frame& frame) {
    std::vector<std::uint8_t> out(frame.leaf.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = frame.leaf[i] >= 0;
    return out;
}

// Frames drawn again with a wait after each pass, for the passes' medians.
constexpr int kPassTimedFrames = 5;

// strata's frames of `scene` into a host framebuffer, timed: the medians
// into `result`. Returns one read-back frame (not timed) for its coverage.
render::Frame timeStrata(const Options& options, const bench::BenchScene& scene, const model::Model& model,
                         const camera::Camera& camera, Result& result) {
    const auto setupStart = Clock::now();
    render::Renderer renderer;
    renderer.setScene(scene.tree, model);
    glFinish();
    result.setupMs += msSince(setupStart);

    // The host's target: renderInto copies the shaded image here.
    gpu::Texture hostColor = gpu::Texture::create2D("bench host color", GL_RGBA8, camera.width, camera.height);
    gpu::Framebuffer host("bench host");
    host.attachTexture(GL_COLOR_ATTACHMENT0, hostColor);
    host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    host.checkComplete();

    render::RenderSettings settings;
    settings.groupOperands = options.groups;
    settings.plainUnions = options.plainUnions;
    settings.lighting = options.lighting;
    settings.outline = options.look.outline;
    // The frames as a program draws them, the GPU waited for once, at the
    // end; then a few more that wait after each pass, for each pass's time.
    std::vector<double> frame, timedFrame, peel, evaluate, normal, plainFrame, shade;
    render::FrameStats last;
    const int timedFrames = std::min(options.frames, kPassTimedFrames);
    for (int i = 0; i < options.warmup + options.frames + timedFrames; ++i) {
        const bool timed = i >= options.warmup + options.frames;
        settings.passTimes = timed;
        const auto start = Clock::now();
        last = renderer.renderInto(host.id(), 0, 0, camera, settings);
        glFinish();
        const double ms = msSince(start);
        if (i < options.warmup) continue;
        if (!timed) {
            frame.push_back(ms);
            continue;
        }
        timedFrame.push_back(ms);
        peel.push_back(last.peelMs);
        evaluate.push_back(last.evaluateMs);
        normal.push_back(last.normalMs);
        plainFrame.push_back(last.plainMs);
        shade.push_back(last.shadeMs);
    }
    gpu::checkErrors();
    result.strataMs = median(frame);
    result.strataMinMs = frame.empty() ? 0.0 : *std::min_element(frame.begin(), frame.end());
    result.strataPassTimedMs = median(timedFrame);
    result.peelMs = median(peel);
    result.evaluateMs = median(evaluate);
    result.normalMs = median(normal);
    result.plainFrameMs = median(plainFrame);
    result.plainFrame = last.plain;
    result.plainBesideLeaves = last.plainBesideLeaves;
    result.shadeMs = median(shade);
    result.textureBytes = last.textureBytes;
    result.operands = last.operands;
    result.tiles = last.tiles;
    result.notes = last.notes;
    for (int layers : last.layersPerLeaf) {
        result.layersTotal += layers;
        result.layersMax = std::max(result.layersMax, layers);
    }
    // renderInto does not count covered pixels; one read-back frame does (not
    // timed), and gives the coverage OpenCSG's is checked against.
    render::Frame frameForCoverage = renderer.render(camera, settings);
    result.coveredPixels = frameForCoverage.stats.coveredPixels;
    return frameForCoverage;
}

// The floor, plain rasterization of the same triangles, timed into `result`.
void timePlain(const Options& options, const bench::BenchScene& scene, const model::Model& model,
               const camera::Camera& camera, Result& result) {
    bench::PlainDraw plain(scene.tree, model, camera.width, camera.height);
    result.triangles = plain.triangles();
    std::vector<double> plainFrames;
    for (int i = 0; i < options.warmup + options.frames; ++i) {
        const double ms = plain.drawFrame(camera);
        if (i >= options.warmup) plainFrames.push_back(ms);
    }
    result.plainMs = median(plainFrames);
    result.plainMinMs = plainFrames.empty() ? 0.0 : *std::min_element(plainFrames.begin(), plainFrames.end());
    // Its vertex buffer (3 float positions a vertex) and RGBA8 + depth 32F target.
    result.plainBytes =
        plain.triangles() * 3 * 3 * sizeof(float) + std::size_t(camera.width) * std::size_t(camera.height) * 8;
}

// `make` builds the scene for a camera carrying the image size.
Result runCase(const Options& options, gpu::Context& context, OpenCsgSide& openCsg, const std::string& name, int k,
               Size size, const std::function<bench::BenchScene(const camera::Camera& base)>& make) {
    Result result;
    result.scene = name;
    result.k = k;
    result.size = size;

    camera::Camera base;
    base.width = size.width;
    base.height = size.height;
    const auto setupStart = Clock::now();
    bench::BenchScene benchScene = make(base);
    const model::Model model = model::buildModel(benchScene.tree);
    const camera::Camera camera =
        benchScene.camera ? *benchScene.camera : camera::defaultCamera(camera::viewBounds(benchScene.tree, model), base);
    result.setupMs = msSince(setupStart);

    const render::Frame frameForCoverage = timeStrata(options, benchScene, model, camera, result);
    // The floor, in the same context, right after.
    timePlain(options, benchScene, model, camera, result);

    if (!openCsg.comparator) {
        result.openCsg.unavailable = openCsg.unavailable;
        return result;
    }
    bench::OpenCsgRunOptions runOptions;
    runOptions.frames = options.frames;
    runOptions.warmup = options.warmup;
    runOptions.capMs = options.openCsgCapMs;
    runOptions.convexity =
        options.openCsgConvexity == "measured" ? bench::ConvexityMode::Measured : bench::ConvexityMode::OpenScad;
    runOptions.renderingLimit = options.openCsgLimit;
    const std::string key = name + " " + std::to_string(size.width) + "x" + std::to_string(size.height);
    result.openCsg = bench::runOpenCsg(*openCsg.comparator, context, benchScene.tree, model, camera,
                                       coverageOf(frameForCoverage), runOptions, key, k, openCsg.caps);
    return result;
}

constexpr double kMiB = 1024.0 * 1024.0;

void printHeader() {
    std::printf("%-12s %4s %9s %7s %10s %10s %7s %9s %9s %9s %9s %8s %9s %9s %10s %-16s %7s\n", "scene", "K",
                "size", "tris", "strata ms", "plain ms", "ratio", "peel ms", "eval ms", "normal ms", "shade ms", "MiB",
                "layers", "covered", "opencsg ms", "best setting", "agree%");
    std::fflush(stdout);
}

// The OpenCSG columns: the best setting's time, name and coverage agreement
// with strata (covered pixels away from edges, Coverage.h); then one line
// with every setting.
void printOpenCsg(const bench::OpenCsgResult& o) {
    // The sum of products OpenSCAD would hand OpenCSG.
    const std::string sum = o.gaveUp ? "normalization stopped at " + std::to_string(o.elements) + " elements"
                                     : std::to_string(o.products) + " products, " + std::to_string(o.primitives) +
                                           " primitives, " + std::to_string(o.elements) + " elements";
    if (o.best < 0) {
        std::printf(" %10s %-16s %7s\n", "n/a", "", "");
    } else {
        const bench::OpenCsgSettingResult& best = o.settings[std::size_t(o.best)];
        std::printf(" %10.2f %-16s %7.2f\n", best.ms, best.name.c_str(), 100.0 * best.agreement.coveredFraction());
    }
    if (!o.unavailable.empty()) {
        std::printf("    opencsg: %s (%s)\n", o.unavailable.c_str(), sum.c_str());
        return;
    }
    std::printf("    opencsg:");
    for (const bench::OpenCsgSettingResult& s : o.settings) {
        if (!s.skipped.empty())
            std::printf(" %s skipped (%s);", s.name.c_str(), s.skipped.c_str());
        else
            std::printf(" %s %.2f%s (%.2f%%);", s.name.c_str(), s.ms, s.overCap ? " over cap" : "",
                        100.0 * s.agreement.coveredFraction());
    }
    std::printf(" %s; convexity %s, max %u\n", sum.c_str(),
                o.convexity == bench::ConvexityMode::Measured ? "measured" : "OpenSCAD's", o.maxConvexity);
}

void printRow(const Result& r) {
    const std::string size = std::to_string(r.size.width) + "x" + std::to_string(r.size.height);
    if (!r.error.empty()) {
        std::printf("%-12s %4d %9s  error: %s\n", r.scene.c_str(), r.k, size.c_str(), r.error.c_str());
    } else {
        const std::string layers = std::to_string(r.layersTotal) + "/" + std::to_string(r.layersMax);
        std::printf("%-12s %4d %9s %7zu %10.2f %10.2f %7.1f %9.2f %9.2f %9.2f %9.2f %8.1f %9s %9zu",
                    r.scene.c_str(), r.k, size.c_str(), r.triangles, r.strataMs, r.plainMs,
                    r.plainMs > 0 ? r.strataMs / r.plainMs : 0.0, r.peelMs, r.evaluateMs, r.normalMs, r.shadeMs,
                    static_cast<double>(r.textureBytes) / kMiB, layers.c_str(), r.coveredPixels);
        printOpenCsg(r.openCsg);
    }
    std::fflush(stdout);
}

std::string today() {
    const std::time_t now = std::time(nullptr);
    char text[32] = {};
    std::strftime(text, sizeof text, "%Y-%m-%d", std::gmtime(&now));
    return text;
}

void writeAgreement(io::JsonWriter& json, const bench::Agreement& a) {
    json.key("agreement").value(a.fraction());
    json.key("agreement_away_from_edges").value(a.interiorFraction());
    json.key("agreement_covered_away_from_edges").value(a.coveredFraction());
    json.key("covered_pixels").value(static_cast<unsigned long long>(a.coveredB));
}

void writeOpenCsg(io::JsonWriter& json, const bench::OpenCsgResult& o) {
    json.key("opencsg").beginObject();
    if (!o.unavailable.empty()) json.key("unavailable").value(o.unavailable);
    json.key("products").value(static_cast<unsigned long long>(o.products));
    json.key("primitives").value(static_cast<unsigned long long>(o.primitives));
    json.key("normalize_elements").value(static_cast<unsigned long long>(o.elements));
    json.key("normalize_gave_up").value(o.gaveUp);
    json.key("convexity").value(o.convexity == bench::ConvexityMode::Measured ? "measured" : "openscad");
    if (o.best >= 0) {
        const bench::OpenCsgSettingResult& best = o.settings[std::size_t(o.best)];
        json.key("best").value(best.name);
        json.key("best_ms").value(best.ms);
        writeAgreement(json, best.agreement);
        json.key("max_convexity").value(static_cast<int>(o.maxConvexity));
        json.key("buffer_bytes").value(static_cast<unsigned long long>(o.bufferBytes));
    }
    json.key("settings").beginArray();
    for (const bench::OpenCsgSettingResult& s : o.settings) {
        json.beginObject();
        json.key("name").value(s.name);
        if (!s.skipped.empty()) {
            json.key("skipped").value(s.skipped);
        } else {
            json.key("ms").value(s.ms);
            json.key("min_ms").value(s.minMs);
            json.key("frames").value(s.frames);
            json.key("over_cap").value(s.overCap);
            writeAgreement(json, s.agreement);
        }
        json.endObject();
    }
    json.endArray();
    json.endObject();
}

std::string toJson(const Options& options, const gpu::Context& context, const OpenCsgSide& openCsg,
                   const std::vector<Result>& results) {
    io::JsonWriter json(2);
    json.beginObject();
    json.key("tool").value("strata-bench");
    json.key("date").value(today());
    json.key("renderer").value(context.renderer());
    json.key("gl_version").value(context.version());
    if (openCsg.comparator) {
        json.key("opencsg_renderer").value(std::string(bench::openCsgVersion()) + ", " +
                                           openCsg.comparator->renderer());
        json.key("opencsg_context").value(openCsg.comparator->context());
    } else
        json.key("opencsg_unavailable").value(openCsg.unavailable);
    json.key("opencsg_cap_ms").value(options.openCsgCapMs);
    json.key("opencsg_limit").value(static_cast<unsigned long long>(options.openCsgLimit));
    json.key("opencsg_normalize_limit").value(static_cast<unsigned long long>(2 * options.openCsgLimit));
    json.key("frames").value(options.frames);
    json.key("warmup").value(options.warmup);
    json.key("steady_heap").value(options.steadyHeap);
    json.key("huge_pages").value(apps::startedWithHugePages());
    json.key("convex_groups").value(options.groups);
    json.key("plain_unions").value(options.plainUnions);
    json.key("light").value(std::string(render::lightingName(options.lighting)));
    json.key("outline").value(options.look.outline);
    json.key("seed").value(options.seed);
    json.key("results").beginArray();
    for (const Result& r : results) {
        json.beginObject();
        json.key("scene").value(r.scene);
        json.key("k").value(r.k);
        json.key("width").value(r.size.width);
        json.key("height").value(r.size.height);
        if (!r.error.empty()) {
            json.key("error").value(r.error);
            json.endObject();
            continue;
        }
        json.key("triangles").value(static_cast<unsigned long long>(r.triangles));
        json.key("operands").value(r.operands);
        json.key("setup_ms").value(r.setupMs);
        json.key("strata_ms").value(r.strataMs);
        json.key("strata_min_ms").value(r.strataMinMs);
        json.key("strata_pass_timed_ms").value(r.strataPassTimedMs);
        json.key("peel_ms").value(r.peelMs);
        json.key("evaluate_ms").value(r.evaluateMs);
        json.key("normal_ms").value(r.normalMs);
        json.key("plain_frame").value(r.plainFrame);
        json.key("plain_beside_leaves").value(static_cast<std::uint64_t>(r.plainBesideLeaves));
        json.key("plain_frame_ms").value(r.plainFrameMs);
        json.key("shade_ms").value(r.shadeMs);
        json.key("plain_ms").value(r.plainMs);
        json.key("plain_min_ms").value(r.plainMinMs);
        json.key("plain_bytes").value(static_cast<unsigned long long>(r.plainBytes));
        json.key("ratio").value(r.plainMs > 0 ? r.strataMs / r.plainMs : 0.0);
        json.key("texture_bytes").value(static_cast<unsigned long long>(r.textureBytes));
        json.key("layers_total").value(r.layersTotal);
        json.key("layers_max").value(r.layersMax);
        json.key("covered_pixels").value(static_cast<unsigned long long>(r.coveredPixels));
        json.key("tiles").value(r.tiles);
        json.key("notes").beginArray();
        for (const std::string& note : r.notes) json.value(note);
        json.endArray();
        writeOpenCsg(json, r.openCsg);
        json.endObject();
    }
    json.endArray();
    json.endObject();
    return json.str();
}

// The command line into `options`; the option of --scenes, which says
// whether it was given.
CLI::Option* addOptions(CLI::App& app, Options& options) {
    CLI::Option* scenes =
        app.add_option("--scenes", options.scenes, "scenes: cheese, stack, intersection, deep, tori, mesh, blowup")
            ->delimiter(',')
            ->check(CLI::IsMember(bench::sceneNames()));
    app.add_option("--files", options.files,
                   "scene files (.csg, .scad, .stl, .obj, .off, .ply) to time as well, from OpenSCAD's default "
                   "view; alone, without --scenes, only these")
        ->delimiter(',');
    apps::addDefineOption(app, options.defines);
    app.add_option("--k", options.ks, "operand counts K")->delimiter(',')->check(CLI::Range(1, 100000));
    app.add_option("--size", options.sizes, "image sizes WxH")->delimiter(',');
    app.add_option("--frames", options.frames, "timed frames per case")->check(CLI::Range(1, 100000));
    app.add_option("--warmup", options.warmup, "untimed frames first")->check(CLI::Range(0, 100000));
    app.add_option("--seed", options.seed, "seed of the random scenes");
    app.add_option("--json", options.json, "also write every figure as one JSON object to FILE");
    app.add_flag("!--no-opencsg", options.openCsg, "leave OpenCSG out");
    app.add_option("--opencsg-cap-ms", options.openCsgCapMs,
                   "an OpenCSG setting with a frame over this many ms is skipped for larger K")
        ->check(CLI::PositiveNumber);
    app.add_option("--opencsg-convexity", options.openCsgConvexity,
                   "OpenCSG's convexity of each primitive: openscad (the file's convexity argument, else 1, as "
                   "OpenSCAD passes it) or measured (counted in the view for each non-convex leaf)")
        ->check(CLI::IsMember({"openscad", "measured"}));
    app.add_option("--opencsg-context", options.openCsgContext,
                   "OpenCSG's compatibility context: auto (GLX where there is an X display, else EGL), glx "
                   "(a hidden GLFW window) or egl (EGL without a surface, also where there is a display)")
        ->check(CLI::IsMember({"auto", "glx", "egl"}));
    app.add_option("--opencsg-limit", options.openCsgLimit,
                   "OpenSCAD's \"Turn off rendering at\" elements: a sum of more primitives is not drawn with "
                   "OpenCSG, and the normalization gives up at twice as many elements")
        ->check(CLI::Range(std::size_t(1), std::size_t(100000000)));
    app.add_flag("!--glibc-heap", options.steadyHeap,
                 "leave glibc's adaptive malloc thresholds as they are (frame times on llvmpipe may then jump "
                 "between runs)");
    app.add_flag("!--no-groups", options.groups,
                 "peel every convex operand of an intersection on its own, not the intersection as one operand "
                 "(to measure what grouping gains)");
    app.add_flag("!--no-plain", options.plainUnions,
                 "run every pass on a union seen from outside too, not its plain depth-tested draw (to measure "
                 "what the plain path gains)");
    apps::addLookOptions(app, options.look);
    return scenes;
}

// OpenCSG's comparator where it was built in and opens, else why not.
// Leaves strata's context current.
OpenCsgSide openOpenCsg(const Options& options, gpu::Context& context) {
    OpenCsgSide openCsg;
    if (!options.openCsg) {
        openCsg.unavailable = "OpenCSG left out (--no-opencsg)";
        return openCsg;
    }
    try {
        const bench::CompatContext kind = options.openCsgContext == "glx"   ? bench::CompatContext::Glx
                                          : options.openCsgContext == "egl" ? bench::CompatContext::Egl
                                                                            : bench::CompatContext::Auto;
        openCsg.comparator = bench::openOpenCsgComparator(kind);
        std::printf("# %s: %s (%s)\n", bench::openCsgVersion(), openCsg.comparator->renderer().c_str(),
                    openCsg.comparator->context().c_str());
    } catch (const std::exception& e) {
        openCsg.unavailable = std::string("OpenCSG unavailable: ") + e.what();
        std::printf("# %s\n", openCsg.unavailable.c_str());
    }
    context.makeCurrent();  // opening the comparator released strata's context
    return openCsg;
}

// Every case, a row printed as each ends: per size, the seeded scenes for
// each K, then the scene files.
std::vector<Result> runAll(const Options& options, gpu::Context& context, OpenCsgSide& openCsg,
                           const std::vector<Size>& sizes, const std::vector<scene::Tree>& fileTrees) {
    std::vector<Result> results;
    auto run = [&](const std::string& name, int k, Size size,
                   const std::function<bench::BenchScene(const camera::Camera&)>& make) {
        Result result;
        try {
            result = runCase(options, context, openCsg, name, k, size, make);
        } catch (const std::exception& e) {
            result.scene = name;
            result.k = k;
            result.size = size;
            result.error = e.what();
        }
        printRow(result);
        results.push_back(std::move(result));
    };
    for (const Size& size : sizes) {
        for (const std::string& name : options.scenes)
            for (int k : options.ks)
                run(name, k, size, [&](const camera::Camera& base) {
                    return bench::makeScene(name, k, options.seed, base);
                });
        for (std::size_t f = 0; f < fileTrees.size(); ++f) {
            const scene::Tree& tree = fileTrees[f];
            run(std::filesystem::path(options.files[f]).filename().string(), static_cast<int>(tree.leaves.size()),
                size, [&](const camera::Camera&) { return bench::BenchScene{tree, std::nullopt}; });
        }
    }
    return results;
}

}  // namespace

int main(int argc, char** argv) {
    apps::runWithHugePages(argv);  // llvmpipe's textures on huge pages, as glibc gives them only on request
    Options options;
    CLI::App app{"strata-bench: strata's frame times against a plain depth-tested draw"};
    const CLI::Option* scenes = addOptions(app, options);
    CLI11_PARSE(app, argc, argv);
    try {
        apps::checkDefines(options.defines, options.files);
        options.lighting = apps::checkedLighting(options.look);
    } catch (const apps::UsageError& e) {
        std::cerr << "strata-bench: " << e.message << '\n';
        return 2;
    }
    const std::string heap = steadyHeap(options.steadyHeap) +
                             (apps::startedWithHugePages() ? "; transparent huge pages on request (glibc.malloc.hugetlb=1)" : "");
    if (!options.files.empty() && scenes->count() == 0) options.scenes.clear();

    try {
        // Loaded first, so a bad file fails before minutes of frames.
        std::vector<scene::Tree> fileTrees;
        for (const std::string& path : options.files) fileTrees.push_back(scene::loadSceneFile(path, options.defines));

        std::vector<Size> sizes;
        for (const std::string& s : options.sizes) sizes.push_back(parseSize(s));

        // Opened first, so an unwritable path fails before minutes of frames.
        std::ofstream jsonOut;
        if (!options.json.empty()) {
            jsonOut.open(options.json);
            if (!jsonOut) throw Error("--json: cannot write '" + options.json + "'");
        }

        gpu::ContextOptions contextOptions;
        contextOptions.debug = false;  // debug output costs time; errors are still checked
        gpu::Context context(contextOptions);
        std::printf("# %s, %s; median of %d frames after %d warm-up, glFinish per frame; passes: median of %d "
                    "more frames with a glFinish after each; %s\n",
                    context.renderer().c_str(), context.version().c_str(), options.frames, options.warmup,
                    std::min(options.frames, kPassTimedFrames), heap.c_str());
        OpenCsgSide openCsg = openOpenCsg(options, context);
        // Ascending K, so a setting over the time cap is skipped for every larger K.
        std::sort(options.ks.begin(), options.ks.end());
        printHeader();
        const std::vector<Result> results = runAll(options, context, openCsg, sizes, fileTrees);

        if (jsonOut.is_open()) {
            jsonOut << toJson(options, context, openCsg, results) << '\n';
            jsonOut.close();
            if (!jsonOut) throw Error("--json: cannot write '" + options.json + "'");
        }
        const bool anyError = std::any_of(results.begin(), results.end(),
                                          [](const Result& r) { return !r.error.empty(); });
        return anyError ? 1 : 0;
    } catch (const std::exception& e) {
        std::cerr << "strata-bench: " << e.what() << '\n';
        return 1;
    }
}
