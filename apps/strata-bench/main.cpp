// strata-bench: frame times of strata's renderer on seeded scenes built in
// code (Scenes.h), against the floor of drawing the same triangles once with
// a depth test (PlainDraw.h), in the same process and GL context.
// Run by hand (docs/benchmarks.md); never by CI.
//
//   strata-bench [--scenes cheese,stack] [--k 1,8,32] [--size 1024x768,512x512]
//                [--frames 10] [--warmup 2] [--seed 1] [--json FILE]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "PlainDraw.h"
#include "Scenes.h"
#include "strata/core/Error.h"
#include "strata/geometry/Model.h"
#include "strata/gpu/Check.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"
#include "strata/io/Json.h"
#include "strata/render/Camera.h"
#include "strata/render/Renderer.h"
#include "strata/render/ViewBounds.h"

namespace {

using namespace strata;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

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
        if (w < 1 || h < 1 || w > 16384 || h > 16384) throw std::invalid_argument("range");
        return {w, h};
    } catch (const std::exception&) {
        throw Error("--size: expected WxH with 1 <= W, H <= 16384, got '" + text + "'");
    }
}

struct Options {
    std::vector<std::string> scenes = bench::sceneNames();
    std::vector<int> ks{1, 8, 32, 64, 128, 256};
    std::vector<std::string> sizes{"1024x768"};
    int frames = 10;
    int warmup = 2;
    unsigned seed = 1;
    std::string json;
};

struct Result {
    std::string scene;
    int k = 0;
    Size size;
    std::size_t triangles = 0;
    int operands = 0;
    double setupMs = 0;                    // geometry + setScene
    double strataMs = 0, strataMinMs = 0;  // wall clock per frame, glFinish included
    double peelMs = 0, evaluateMs = 0, shadeMs = 0;  // FrameStats, medians
    double plainMs = 0, plainMinMs = 0;
    std::size_t textureBytes = 0;
    int layersTotal = 0, layersMax = 0;
    std::size_t coveredPixels = 0;
    int tiles = 1;
    std::vector<std::string> notes;
    std::string error;                     // non-empty: this case failed
};

Result runCase(const Options& options, const std::string& name, int k, Size size) {
    Result result;
    result.scene = name;
    result.k = k;
    result.size = size;

    render::Camera base;
    base.width = size.width;
    base.height = size.height;
    const auto setupStart = Clock::now();
    bench::BenchScene benchScene = bench::makeScene(name, k, options.seed, base);
    const geometry::Model model = geometry::buildModel(benchScene.tree);
    const render::Camera camera =
        benchScene.camera ? *benchScene.camera : render::defaultCamera(render::viewBounds(benchScene.tree, model), base);

    render::Renderer renderer;
    renderer.setScene(benchScene.tree, model);
    glFinish();
    result.setupMs = msSince(setupStart);

    // The host's target: renderInto copies the shaded image here.
    gpu::Texture hostColor = gpu::Texture::create2D("bench host color", GL_RGBA8, size.width, size.height);
    gpu::Framebuffer host("bench host");
    host.attachTexture(GL_COLOR_ATTACHMENT0, hostColor);
    host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    host.checkComplete();

    const render::RenderSettings settings;
    std::vector<double> frame, peel, evaluate, shade;
    render::FrameStats last;
    for (int i = 0; i < options.warmup + options.frames; ++i) {
        const auto start = Clock::now();
        last = renderer.renderInto(host.id(), 0, 0, camera, settings);
        glFinish();
        const double ms = msSince(start);
        if (i < options.warmup) continue;
        frame.push_back(ms);
        peel.push_back(last.peelMs);
        evaluate.push_back(last.evaluateMs);
        shade.push_back(last.shadeMs);
    }
    gpu::checkErrors();
    result.strataMs = median(frame);
    result.strataMinMs = frame.empty() ? 0.0 : *std::min_element(frame.begin(), frame.end());
    result.peelMs = median(peel);
    result.evaluateMs = median(evaluate);
    result.shadeMs = median(shade);
    result.textureBytes = last.textureBytes;
    result.operands = last.operands;
    result.tiles = last.tiles;
    result.notes = last.notes;
    for (int layers : last.layersPerLeaf) {
        result.layersTotal += layers;
        result.layersMax = std::max(result.layersMax, layers);
    }
    // renderInto does not count covered pixels; one read-back frame does (not timed).
    result.coveredPixels = renderer.render(camera, settings).stats.coveredPixels;

    // The floor, in the same context, right after.
    bench::PlainDraw plain(benchScene.tree, model, size.width, size.height);
    result.triangles = plain.triangles();
    std::vector<double> plainFrames;
    for (int i = 0; i < options.warmup + options.frames; ++i) {
        const double ms = plain.drawFrame(camera);
        if (i >= options.warmup) plainFrames.push_back(ms);
    }
    result.plainMs = median(plainFrames);
    result.plainMinMs = plainFrames.empty() ? 0.0 : *std::min_element(plainFrames.begin(), plainFrames.end());
    return result;
}

constexpr double kMiB = 1024.0 * 1024.0;

void printHeader() {
    std::printf("%-12s %4s %9s %7s %10s %10s %7s %9s %9s %9s %8s %9s %9s\n", "scene", "K", "size",
                "tris", "strata ms", "plain ms", "ratio", "peel ms", "eval ms", "shade ms", "MiB",
                "layers", "covered");
    std::fflush(stdout);
}

void printRow(const Result& r) {
    const std::string size = std::to_string(r.size.width) + "x" + std::to_string(r.size.height);
    if (!r.error.empty()) {
        std::printf("%-12s %4d %9s  error: %s\n", r.scene.c_str(), r.k, size.c_str(), r.error.c_str());
    } else {
        const std::string layers = std::to_string(r.layersTotal) + "/" + std::to_string(r.layersMax);
        std::printf("%-12s %4d %9s %7zu %10.2f %10.2f %7.1f %9.2f %9.2f %9.2f %8.1f %9s %9zu\n",
                    r.scene.c_str(), r.k, size.c_str(), r.triangles, r.strataMs, r.plainMs,
                    r.plainMs > 0 ? r.strataMs / r.plainMs : 0.0, r.peelMs, r.evaluateMs, r.shadeMs,
                    static_cast<double>(r.textureBytes) / kMiB, layers.c_str(), r.coveredPixels);
    }
    std::fflush(stdout);
}

std::string today() {
    const std::time_t now = std::time(nullptr);
    char text[32] = {};
    std::strftime(text, sizeof text, "%Y-%m-%d", std::gmtime(&now));
    return text;
}

std::string toJson(const Options& options, const gpu::Context& context, const std::vector<Result>& results) {
    io::JsonWriter json(2);
    json.beginObject();
    json.key("tool").value("strata-bench");
    json.key("date").value(today());
    json.key("renderer").value(context.renderer());
    json.key("gl_version").value(context.version());
    json.key("frames").value(options.frames);
    json.key("warmup").value(options.warmup);
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
        json.key("peel_ms").value(r.peelMs);
        json.key("evaluate_ms").value(r.evaluateMs);
        json.key("shade_ms").value(r.shadeMs);
        json.key("plain_ms").value(r.plainMs);
        json.key("plain_min_ms").value(r.plainMinMs);
        json.key("ratio").value(r.plainMs > 0 ? r.strataMs / r.plainMs : 0.0);
        json.key("texture_bytes").value(static_cast<unsigned long long>(r.textureBytes));
        json.key("layers_total").value(r.layersTotal);
        json.key("layers_max").value(r.layersMax);
        json.key("covered_pixels").value(static_cast<unsigned long long>(r.coveredPixels));
        json.key("tiles").value(r.tiles);
        json.key("notes").beginArray();
        for (const std::string& note : r.notes) json.value(note);
        json.endArray();
        json.endObject();
    }
    json.endArray();
    json.endObject();
    return json.str();
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"strata-bench: strata's frame times against a plain depth-tested draw"};
    app.add_option("--scenes", options.scenes, "scenes: cheese, stack, intersection, deep")
        ->delimiter(',')
        ->check(CLI::IsMember(bench::sceneNames()));
    app.add_option("--k", options.ks, "operand counts K")->delimiter(',')->check(CLI::Range(1, 100000));
    app.add_option("--size", options.sizes, "image sizes WxH")->delimiter(',');
    app.add_option("--frames", options.frames, "timed frames per case")->check(CLI::Range(1, 100000));
    app.add_option("--warmup", options.warmup, "untimed frames first")->check(CLI::Range(0, 100000));
    app.add_option("--seed", options.seed, "seed of the random scenes");
    app.add_option("--json", options.json, "also write every figure as one JSON object to FILE");
    CLI11_PARSE(app, argc, argv);

    try {
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
        std::printf("# %s, %s; median of %d frames after %d warm-up, glFinish per frame\n",
                    context.renderer().c_str(), context.version().c_str(), options.frames, options.warmup);
        printHeader();

        std::vector<Result> results;
        for (const Size& size : sizes)
            for (const std::string& name : options.scenes)
                for (int k : options.ks) {
                    Result result;
                    try {
                        result = runCase(options, name, k, size);
                    } catch (const std::exception& e) {
                        result.scene = name;
                        result.k = k;
                        result.size = size;
                        result.error = e.what();
                    }
                    printRow(result);
                    results.push_back(std::move(result));
                }

        if (jsonOut.is_open()) {
            jsonOut << toJson(options, context, results) << '\n';
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
