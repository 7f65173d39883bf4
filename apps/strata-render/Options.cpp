#include "Options.h"

#include <filesystem>

#include <CLI/CLI.hpp>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include "CommandLine.h"
#include "OpenscadOptions.h"
#include "strata/render/Limits.h"
#include "strata/core/Error.h"
#include "strata/io/ExportFormats.h"
#include "strata/io/FlatWriter.h"
#include "strata/remesh/Remesh.h"

namespace strata::apps {
namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool endsWith(const std::string& s, std::string_view suffix) {
    return s.size() > suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return parts;
}

std::string trim(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return {};
    const std::size_t b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

// A whole decimal number, nothing after it.
bool parseInt(const std::string& text, long long& out) {
    const std::string t = trim(text);
    if (t.empty()) return false;
    const char* begin = t.data() + (t[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(begin, t.data() + t.size(), out);
    return ec == std::errc() && end == t.data() + t.size();
}

// A finite real number, nothing after it (strtod accepts what OpenSCAD's users type: 1, -2.5, 1e3).
bool parseReal(const std::string& text, double& out) {
    const std::string t = trim(text);
    if (t.empty()) return false;
    char* end = nullptr;
    out = std::strtod(t.c_str(), &end);
    return end == t.c_str() + t.size() && std::isfinite(out);
}

void parseImageSize(const std::string& text, RenderOptions& options) {
    const auto parts = splitCommas(text);
    long long w = 0, h = 0;
    if (parts.size() != 2 || !parseInt(parts[0], w) || !parseInt(parts[1], h))
        throw UsageError{"--imgsize: expected W,H (two whole numbers), got '" + text + "'"};
    if (w <= 0 || h <= 0)
        throw UsageError{"--imgsize: width and height must be positive, got '" + text + "'"};
    if (w > render::kMaxImageSide || h > render::kMaxImageSide)
        throw UsageError{"--imgsize: at most " + std::to_string(render::kMaxImageSide) + " pixels a side, got '" + text +
                         "'"};
    options.width = static_cast<int>(w);
    options.height = static_cast<int>(h);
}

void parseCamera(const std::string& text, RenderOptions& options) {
    const auto parts = splitCommas(text);
    std::vector<double> numbers;
    for (const std::string& part : parts) {
        double v = 0;
        if (!parseReal(part, v))
            throw UsageError{"--camera: '" + trim(part) + "' is not a finite number (in '" + text + "')"};
        numbers.push_back(v);
    }
    if (numbers.size() != 6 && numbers.size() != 7)
        throw UsageError{"--camera: expected 6 numbers (eye, center) or 7 (translate, rotate, distance), got " +
                         std::to_string(numbers.size())};
    options.camera = std::move(numbers);
}

void parseProjection(const std::string& text, RenderOptions& options) {
    const std::string t = lower(trim(text));
    if (t == "p" || t == "perspective")
        options.projection = camera::Projection::Perspective;
    else if (t == "o" || t == "ortho" || t == "orthogonal" || t == "orthographic")
        options.projection = camera::Projection::Orthographic;
    else
        throw UsageError{"--projection: expected 'p' (perspective) or 'o' (orthographic), got '" + text + "'"};
}

void parseFov(const std::string& text, RenderOptions& options) {
    double fov = 0;
    // Past these the fitted camera's distance leaves floating point.
    if (!parseReal(text, fov) || fov < 0.01 || fov > 179.0)
        throw UsageError{"--fov: expected degrees from 0.01 to 179, got '" + text + "'"};
    options.fovDegrees = fov;
}

void parseLayers(const std::string& text, RenderOptions& options) {
    if (lower(trim(text)) == "auto") {
        options.layers = 0;
        return;
    }
    long long n = 0;
    if (!parseInt(text, n) || n < 1 || n > render::kMaxLayers)
        throw UsageError{"--layers: expected 'auto' or a whole number from 1 to " + std::to_string(render::kMaxLayers) +
                         ", got '" + text + "'"};
    options.layers = static_cast<int>(n);
}

void checkOutputName(const std::string& option, const std::string& path, std::string_view extension) {
    if (path.empty()) throw UsageError{option + ": expected a file name"};
    if (path[0] == '=')  // "-o=x.png": a short option takes no '='
        throw UsageError{option + ": write '" + option + " FILE', without '=' (got '" + path + "')"};
    if (!endsWith(path, extension))
        throw UsageError{option + ": expected a " + std::string(extension) + " file name, got '" + path + "'"};
}

bool sameFile(const std::string& a, const std::string& b);
void checkSceneNames(const RenderOptions& o);

// --export FILE: a mesh or drawing format by its extension.
void checkExport(const RenderOptions& o) {
    if (o.exportPath.empty()) throw UsageError{"--export: expected a file name"};
    if (io::exportFormatOf(o.exportPath) == nullptr)
        throw UsageError{"--export: expected a " + io::extensionList() + " file name, got '" + o.exportPath + "'"};
    for (const std::string* other : {&o.png, &o.depth, &o.normal}) {
        if (!other->empty() && sameFile(*other, o.exportPath)) {
            throw UsageError{"--export and another output name the same file '" + o.exportPath + "'"};
        }
    }
}

// A scene's name in the output names: its file name without folder and extension.
std::string sceneName(const std::string& scene) { return std::filesystem::path(scene).stem().string(); }

// The output names, with the option that gave each.
std::vector<std::pair<const char*, std::string>> outputNames(const RenderOptions& o) {
    std::vector<std::pair<const char*, std::string>> names;
    if (!o.png.empty()) names.emplace_back("-o", o.png);
    if (!o.depth.empty()) names.emplace_back("--depth", o.depth);
    if (!o.normal.empty()) names.emplace_back("--normal", o.normal);
    if (!o.exportPath.empty()) names.emplace_back("--export", o.exportPath);
    return names;
}

// Several scenes: every output name holds %s, and no two scenes share a name
// (they would write one file).
void checkSceneNames(const RenderOptions& o) {
    if (o.scenes.size() < 2) return;
    for (const auto& [option, name] : outputNames(o))
        if (name.find("%s") == std::string::npos)
            throw UsageError{std::string(option) + ": with several scenes the name needs %s, the scene's name (got '" +
                             name + "')"};
    for (std::size_t i = 0; i < o.scenes.size(); ++i)
        for (std::size_t j = i + 1; j < o.scenes.size(); ++j)
            if (sceneName(o.scenes[i]) == sceneName(o.scenes[j]))
                throw UsageError{"'" + o.scenes[i] + "' and '" + o.scenes[j] + "' have one name, '" +
                                 sceneName(o.scenes[i]) + "': their outputs would be one file"};
}

// Whether two output names lead to one file (after "." , ".." and links).
bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    const std::filesystem::path x = std::filesystem::weakly_canonical(a, ec);
    if (ec) return a == b;
    const std::filesystem::path y = std::filesystem::weakly_canonical(b, ec);
    return ec ? a == b : x == y;
}

}  // namespace

RenderOptions forScene(const RenderOptions& options, const std::string& scene) {
    RenderOptions one = options;
    one.scene = scene;
    one.scenes = {scene};
    const std::string name = sceneName(scene);
    for (std::string* output : {&one.png, &one.depth, &one.normal, &one.exportPath}) {
        for (std::size_t at = output->find("%s"); at != std::string::npos; at = output->find("%s", at + name.size()))
            output->replace(at, 2, name);
    }
    return one;
}

ParseResult parseOptions(int argc, char** argv) {
    ParseResult result;
    RenderOptions& o = result.options;

    CLI::App app{"strata-render: image-space CSG rendering, headless (options and outputs: docs/contract.md)", "strata-render"};
    app.option_defaults()->always_capture_default(false);
    std::string imgsize, camera, projection, fov, layers;
    app.add_option("SCENE", o.scenes,
                   "a .csg file (OpenSCAD's CSG export), a .scad file (needs openscad), or one closed "
                   ".stl/.obj/.off/.ply mesh; several: each in turn in this one process, every output name "
                   "holding %s for the scene's name")
        ->required();
    addDefineOption(app, o.defines);
    app.add_option("-o", o.png, "write the shaded image (8-bit RGBA PNG)")->type_name("FILE.png");
    app.add_option("--depth", o.depth, "write the depth AOV (OpenEXR, channel Z)")->type_name("FILE.exr");
    app.add_option("--normal", o.normal, "write the normal AOV (OpenEXR, channels R,G,B)")->type_name("FILE.exr");
    app.add_option("--imgsize", imgsize, "image size in pixels (default 512,512)")->type_name("W,H");
    app.add_option("--camera", camera,
                   "eye and center EX,EY,EZ,CX,CY,CZ, or gimbal TX,TY,TZ,RX,RY,RZ,DIST "
                   "(default: OpenSCAD's view fitted to the scene)")
        ->type_name("NUMBERS");
    app.add_option("--projection", projection, "p (perspective, default) or o (orthographic)")->type_name("p|o");
    app.add_option("--fov", fov, "vertical field of view in degrees (default 22.5)")->type_name("DEG");
    app.add_option("--layers", layers, "depth-peel layers per operand, or auto (default)")->type_name("N|auto");
    app.add_flag("--stats", o.stats, "print one JSON object of figures on stdout");
    app.add_flag("-q,--quiet", o.quiet, "print only errors on stderr: no warnings, progress or a .scad's echo");
    app.add_flag("--reference", o.reference,
                 "find the surfaces with the CPU reference ray caster (Embree) instead of the GPU passes, "
                 "to compare the two on your own scenes (same outputs, same shading)");
    app.add_option("--colorscheme", o.colorScheme, "OpenSCAD colour scheme (default Cornfield)")->type_name("NAME");
    addLookOptions(app, o.look);
    app.add_option("--export", o.exportPath,
                   "write the CSG result as a mesh (binary STL, OFF, OBJ or 3MF, by the extension), or a 2D model's "
                   "as a drawing (SVG or DXF); "
                   "without -o, --depth or --normal nothing is rendered")
        ->type_name("FILE");
    app.add_flag("--export-exact", o.exportExact,
                 "export the exact result, evaluated by CGAL as OpenSCAD's render does (the default)");
    app.add_flag("--export-sampled", o.exportSampled,
                 "export a mesh contoured from the image-space result, sampled on a grid, instead of the exact one");
    std::string exportResolution;
    app.add_option("--export-resolution", exportResolution,
                   "cells along the longest side of the result's box for --export-sampled (default 512, 8 to 4096)")
        ->type_name("N");
    addOpenscadOptions(app);

    static_cast<CliOutcome&>(result) = parseCommandLine(app, argc, argv, "strata-render", [&] {
        checkOpenscadOptions(app, app.count("--camera") != 0);
        o.scene = o.scenes.front();
        checkDefines(o.defines, o.scenes);
        checkSceneNames(o);
        if (!imgsize.empty() || app.count("--imgsize")) parseImageSize(imgsize, o);
        if (app.count("--camera")) parseCamera(camera, o);
        if (app.count("--projection")) parseProjection(projection, o);
        if (app.count("--fov")) parseFov(fov, o);
        if (app.count("--layers")) parseLayers(layers, o);
        if (app.count("-o")) checkOutputName("-o", o.png, ".png");
        if (app.count("--depth")) checkOutputName("--depth", o.depth, ".exr");
        if (app.count("--normal")) checkOutputName("--normal", o.normal, ".exr");
        // Two outputs into one file: the second would silently replace the first.
        if (!o.depth.empty() && sameFile(o.depth, o.normal)) {
            throw UsageError{"--depth and --normal name the same file '" + o.depth + "'"};
        }
        if (app.count("--export")) checkExport(o);
        if (o.exportExact && o.exportSampled) throw UsageError{"--export-exact and --export-sampled: give one of them"};
        if (o.exportExact && o.exportPath.empty()) throw UsageError{"--export-exact: give --export FILE too"};
        if (o.exportSampled && o.exportPath.empty()) throw UsageError{"--export-sampled: give --export FILE too"};
        if (o.exportSampled && io::isFlatPath(o.exportPath))
            throw UsageError{"--export-sampled: a drawing (.svg, .dxf) is always the exact 2D result"};
        if (app.count("--export-resolution")) {
            if (!o.exportSampled) throw UsageError{"--export-resolution: the exact export has no resolution; give --export-sampled too"};
            long long n = 0;
            if (!parseInt(exportResolution, n) || n < remesh::kLeastResolution || n > remesh::kMostResolution)
                throw UsageError{"--export-resolution: expected a whole number from " +
                                 std::to_string(remesh::kLeastResolution) + " to " +
                                 std::to_string(remesh::kMostResolution) + ", got '" + exportResolution + "'"};
            o.exportResolution = static_cast<int>(n);
        }
        if (app.count("--colorscheme")) o.colorScheme = checkedColorScheme(o.colorScheme);
        o.lighting = checkedLighting(o.look);
    });
    return result;
}

}  // namespace strata::apps
