// strata-view run with --script under a display (CI: xvfb-run), its
// screenshots compared pixel for pixel with strata-render's images at the
// camera and settings the viewer reports. Exact equality is expected: both
// draw through the same Renderer at the same camera (the viewer reports its
// eye and centre as shortest round-trip decimals), and PNG is lossless.

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::lineCount;
using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kView = STRATA_VIEW_EXE;
const std::string kRender = STRATA_RENDER_EXE;

// A cube with a spherical hole (concave: two peel layers) and a cylinder beside
// it. Line 1 is blank so that the difference (line 2) is not on the root's line.
const std::string kScene = R"(
difference() {
	cube(size = [10, 10, 10], center = true);
	sphere(r = 6.5, $fn = 48);
}
multmatrix([[1, 0, 0, 12], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {
	cylinder(h = 8, r1 = 3, r2 = 3, center = true, $fn = 32);
}
)";
// kScene without the cylinder, and without the difference.
const std::string kNoCylinder = R"(
difference() {
	cube(size = [10, 10, 10], center = true);
	sphere(r = 6.5, $fn = 48);
}
)";
const std::string kOnlyCylinder = R"(
multmatrix([[1, 0, 0, 12], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {
	cylinder(h = 8, r1 = 3, r2 = 3, center = true, $fn = 32);
}
)";

struct Image {
    int width = 0, height = 0;
    std::vector<unsigned char> rgba;
    bool operator==(const Image&) const = default;
};

Image readPng(const std::string& path) {
    Image image;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return image;
    const OIIO::ImageSpec& spec = in->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.rgba.resize(static_cast<std::size_t>(spec.width) * spec.height * 4);
    if (spec.nchannels != 4 || !in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, image.rgba.data())) return {};
    return image;
}

// Pixels unlike the top-left one (the background): the image shows something.
int drawnPixels(const Image& image) {
    int n = 0;
    for (std::size_t k = 0; k < image.rgba.size(); k += 4)
        n += !std::equal(image.rgba.begin() + static_cast<std::ptrdiff_t>(k),
                         image.rgba.begin() + static_cast<std::ptrdiff_t>(k) + 4, image.rgba.begin());
    return n;
}

int differingPixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return -1;
    int n = 0;
    for (std::size_t k = 0; k < a.rgba.size(); k += 4)
        n += !std::equal(a.rgba.begin() + static_cast<std::ptrdiff_t>(k),
                         a.rgba.begin() + static_cast<std::ptrdiff_t>(k) + 4, b.rgba.begin() + static_cast<std::ptrdiff_t>(k));
    return n;
}

// The pixel at column x, row y (row 0 at the top).
const unsigned char* pixelAt(const Image& image, int x, int y) {
    return image.rgba.data() + (static_cast<std::size_t>(y) * image.width + x) * 4;
}

bool isRgb(const Image& image, int x, int y, int r, int g, int b) {
    const unsigned char* p = pixelAt(image, x, y);
    return p[0] == r && p[1] == g && p[2] == b;
}

// The "--camera=..." lines the script printed, in order.
std::vector<std::string> cameraLines(const std::string& out) {
    std::vector<std::string> lines;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);)
        if (line.starts_with("--camera=")) lines.push_back(line);
    return lines;
}

// The figures of a "print load" line, by name; empty when the line is not one.
std::map<std::string, double> loadFigures(const std::string& line) {
    std::smatch m;
    if (!std::regex_match(line, m,
                          std::regex(R"(load_ms (\S+) handover_ms (\S+) upload_ms (\S+) first_frame_ms (\S+) )"
                                     R"(total_ms (\S+) poll_ms (\S+))")))
        return {};
    return {{"load", std::stod(m[1])},   {"handover", std::stod(m[2])}, {"upload", std::stod(m[3])},
            {"frame", std::stod(m[4])}, {"total", std::stod(m[5])},    {"poll", std::stod(m[6])}};
}

// The operands of each "print stats" line, in order.
std::vector<int> statsOperands(const std::string& out) {
    std::vector<int> operands;
    std::smatch m;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, std::regex(R"( operands (\d+)$)"))) operands.push_back(std::stoi(m[1]));
    return operands;
}

class StrataView : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
        // The viewer keeps its recent files under XDG_STATE_HOME: the test's own.
        setenv("XDG_STATE_HOME", (dir / "state").c_str(), 1);
    }

    ProcessResult view(const std::string& scene, const std::string& script) {
        const std::string path = dir / "script.txt";
        std::ofstream(path) << script;
        return runProcess({kView, scene, "--script", path});
    }

    // strata-render's image of `scene`, at 320x240 with `args` added.
    Image render(const std::string& scene, std::vector<std::string> args) {
        const std::string out = dir / ("render-" + std::to_string(++renders) + ".png");
        std::vector<std::string> argv{kRender, scene, "--imgsize", "320,240", "-o", out};
        argv.insert(argv.end(), args.begin(), args.end());
        const ProcessResult r = runProcess(argv);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readPng(out);
    }

    // Asserts `shot` shows the model and equals strata-render's image exactly.
    void expectSameAsRender(const Image& shot, const Image& rendered) {
        EXPECT_EQ(shot.width, 320);
        EXPECT_EQ(shot.height, 240);
        EXPECT_GT(drawnPixels(shot), 1000) << "the screenshot is (nearly) all background";
        EXPECT_EQ(differingPixels(shot, rendered), 0);
    }

    TempDir dir;
    int renders = 0;
};

TEST_F(StrataView, ScreenshotEqualsStrataRenderAtTheReportedCamera) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "print camera\n"
                                 "screenshot default.png\n"
                                 "layers 1\n"
                                 "projection o\n"
                                 "colorscheme Tomorrow Night\n"
                                 "screenshot settings.png\n"
                                 "light openscad\n"
                                 "show outline off\n"
                                 "screenshot look.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cams = cameraLines(r.out);
    ASSERT_EQ(cams.size(), 1u) << r.out;
    // The default view is strata-render's default camera, to the bit.
    expectSameAsRender(readPng(dir / "default.png"), render(scene, {}));
    expectSameAsRender(readPng(dir / "default.png"), render(scene, {cams[0]}));
    const Image settings = readPng(dir / "settings.png");
    expectSameAsRender(settings, render(scene, {cams[0], "--layers", "1", "--projection", "o", "--colorscheme",
                                                "Tomorrow Night"}));
    EXPECT_GT(differingPixels(settings, readPng(dir / "default.png")), 1000);  // the settings took effect
    const Image look = readPng(dir / "look.png");
    expectSameAsRender(look, render(scene, {cams[0], "--layers", "1", "--projection", "o", "--colorscheme",
                                            "Tomorrow Night", "--light", "openscad", "--no-outline"}));
    EXPECT_GT(differingPixels(look, settings), 1000);
}

TEST_F(StrataView, OrbitPanZoomEqualStrataRenderAtTheReportedCamera) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "camera 0,0,0,60,0,30,80\n"
                                 "print camera\n"
                                 "screenshot before.png\n"
                                 "orbit 40 -25\n"
                                 "pan 12 -6\n"
                                 "zoom 1.5\n"
                                 "print camera\n"
                                 "screenshot after.png\n"
                                 "preset top\n"
                                 "print camera\n"
                                 "screenshot top.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cams = cameraLines(r.out);
    ASSERT_EQ(cams.size(), 3u) << r.out;
    const Image before = readPng(dir / "before.png"), after = readPng(dir / "after.png");
    expectSameAsRender(before, render(scene, {"--camera=0,0,0,60,0,30,80"}));
    expectSameAsRender(after, render(scene, {cams[1]}));
    expectSameAsRender(readPng(dir / "top.png"), render(scene, {cams[2]}));
    EXPECT_GT(differingPixels(before, after), 1000);  // the drag moved the view
    EXPECT_NE(cams[0], cams[1]);
}

TEST_F(StrataView, ToggledNodeEqualsTheSceneWithoutIt) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "camera 6,-60,30,6,0,0\n"
                                 "toggle line:7\n"
                                 "screenshot no-cylinder.png\n"
                                 "toggle line:7\n"
                                 "toggle line:2\n"
                                 "screenshot only-cylinder.png\n"
                                 "toggle line:2\n"
                                 "screenshot all.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string camera = "--camera=6,-60,30,6,0,0";
    expectSameAsRender(readPng(dir / "no-cylinder.png"), render(dir.write("b.csg", kNoCylinder), {camera}));
    expectSameAsRender(readPng(dir / "only-cylinder.png"), render(dir.write("c.csg", kOnlyCylinder), {camera}));
    expectSameAsRender(readPng(dir / "all.png"), render(scene, {camera}));
}

TEST_F(StrataView, HighlightEqualsTheSceneWithTheModifier) {
    const std::string scene = dir.write("a.csg", kScene);
    std::string marked = kScene;
    marked.insert(marked.find("difference"), 1, '#');
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "camera 6,-60,30,6,0,0\n"
                                 "highlight line:2\n"
                                 "screenshot highlight.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image shot = readPng(dir / "highlight.png");
    expectSameAsRender(shot, render(dir.write("m.csg", marked), {"--camera=6,-60,30,6,0,0"}));
    EXPECT_GT(differingPixels(shot, render(scene, {"--camera=6,-60,30,6,0,0"})), 1000);
}

TEST_F(StrataView, ReloadShowsTheNewFileAndKeepsTheLastGoodOneOnAnError) {
    const std::string scene = dir.write("a.csg", kScene);
    const std::string second = dir.write("second.csg", kNoCylinder);
    const std::string broken = dir.write("broken.csg", "cube(size = [1, 1, 1]);\nsphere(r = );\n");
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "camera 6,-60,30,6,0,0\n"
                                 "screenshot first.png\n"
                                 "copy second.csg a.csg\n"
                                 "wait-reload\n"
                                 "screenshot second.png\n"
                                 "print error\n"
                                 "copy broken.csg a.csg\n"
                                 "wait-reload\n"
                                 "screenshot broken.png\n"
                                 "print error\n"
                                 "copy second.csg a.csg\n"
                                 "wait-reload\n"
                                 "print error\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string camera = "--camera=6,-60,30,6,0,0";
    const Image first = readPng(dir / "first.png"), shot = readPng(dir / "second.png");
    expectSameAsRender(first, render(dir.write("orig.csg", kScene), {camera}));  // a.csg itself is replaced by now
    expectSameAsRender(shot, render(second, {camera}));
    EXPECT_GT(differingPixels(first, shot), 1000);
    // The broken file: the last good image stays, and the parser's one-line error is reported.
    EXPECT_EQ(readPng(dir / "broken.png"), shot);
    const std::string parseError = runProcess({kRender, broken}).err;  // "broken.csg:2:12: ..."
    const std::string expected = scene + parseError.substr(broken.size());
    EXPECT_EQ(r.out, "no error\n" + expected + "no error\n");
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
}

// print load: the way of the last shown load to the screen, for a script's
// open as for a reload; its parts lie inside its total.
TEST_F(StrataView, PrintLoadGivesTheLastReloadsFiguresAndItsFrameShowsTheNewModel) {
    const std::string start = dir.write("start.csg", kOnlyCylinder);
    dir.write("a.csg", kScene);
    dir.write("second.csg", kNoCylinder);
    const ProcessResult r = view(start,
                                 "size 160 120\n"
                                 "print load\n"
                                 "open a.csg\n"
                                 "print load\n"
                                 "print stats\n"
                                 "copy second.csg a.csg\n"
                                 "wait-reload\n"
                                 "print load\n"
                                 "print stats\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> lines;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_EQ(lines.size(), 5u) << r.out;
    // The scene named on the command line is loaded before the window opens: no figures.
    EXPECT_EQ(lines[0], "no load");
    for (const std::string& line : {lines[1], lines[3]}) {
        const std::map<std::string, double> f = loadFigures(line);
        ASSERT_EQ(f.size(), 6u) << line;
        for (const auto& [name, value] : f) EXPECT_GE(value, 0.0) << name << " in " << line;
        EXPECT_GT(f.at("poll"), 0.0) << line;
        // Printed to a microsecond each: allow their rounding.
        EXPECT_GE(f.at("total") + 1e-5, f.at("load") + f.at("handover") + f.at("upload") + f.at("frame")) << line;
    }
    // The frame after the open shows a.csg (cube, sphere, cylinder), the one
    // after the reload second.csg (no cylinder).
    EXPECT_EQ(statsOperands(r.out), (std::vector<int>{3, 2})) << r.out;
}

TEST_F(StrataView, DoubleClickRecentresOnTheSurfaceUnderThePixel) {
    const std::string scene = dir.write("cube.csg", "cube(size = [10, 10, 10], center = true);\n");
    // Looking along +Y at the face y = -5; pixel (200, 90) of 320x240 hits it.
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "camera 0,-50,0,0,0,0\n"
                                 "double-click 200 90\n"
                                 "print camera\n"
                                 "double-click 2 2\n"
                                 "print camera\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cams = cameraLines(r.out);
    ASSERT_EQ(cams.size(), 2u) << r.out;
    std::vector<double> n;
    std::istringstream parts(cams[0].substr(9));
    for (std::string part; std::getline(parts, part, ',');) n.push_back(std::stod(part));
    ASSERT_EQ(n.size(), 6u);
    // The new centre is on the face (depth is float: 45 units to ~1e-5 relative), to the right of and above the old one.
    EXPECT_NEAR(n[4], -5.0, 1e-3);
    EXPECT_GT(n[3], 0.5);
    EXPECT_GT(n[5], 0.5);
    EXPECT_NEAR(n[1] - n[4], -50.0, 1e-9);  // direction and distance kept
    EXPECT_EQ(cams[1], cams[0]);            // the background: nothing to centre on
}

TEST_F(StrataView, OpeningAnotherFileFramesItAsAFirstFile) {
    // After a small cube, a large scene opened by the script is framed as if
    // it had been opened first: the camera of the cube would put the eye
    // inside it.
    const std::string small = dir.write("small.csg", "cube(size = [1, 1, 1], center = true);\n");
    const std::string large = dir.write("large.csg", kScene);
    const ProcessResult opened = view(small,
                                      "size 320 240\n"
                                      "zoom 3\n"
                                      "open large.csg\n"
                                      "screenshot opened.png\n"
                                      "print camera\n");
    ASSERT_EQ(opened.exitCode, 0) << opened.err;
    const ProcessResult first = view(large, "size 320 240\nscreenshot first.png\nprint camera\n");
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_EQ(opened.out, first.out);
    EXPECT_EQ(differingPixels(readPng(dir / "opened.png"), readPng(dir / "first.png")), 0);
}

TEST_F(StrataView, AScriptOpeningAMissingFileSaysSoOnce) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene, "size 32 32\nopen missing.csg\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(r.err.starts_with(dir / "script.txt:2:1: ")) << r.err;
}

TEST_F(StrataView, ScriptErrorsAtRunTimeNameTheCommand) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene, "size 32 32\ntoggle 999\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(r.err.starts_with(dir / "script.txt:2:1: no node 999")) << r.err;
}

TEST_F(StrataView, ExportWritesWhatStrataRenderExports) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r =
        view(scene, "size 64 64\nexport view.off\nexport-sampled sampled.off\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ProcessResult cli = runProcess({kRender, scene, "--export", dir / "render.off"});
    ASSERT_EQ(cli.exitCode, 0) << cli.err;
    // The viewer samples with the CPU reference: strata-render --reference.
    const ProcessResult sampled =
        runProcess({kRender, scene, "--export", dir / "render-sampled.off", "--export-sampled", "--reference"});
    ASSERT_EQ(sampled.exitCode, 0) << sampled.err;
    auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    const std::string viewed = bytes(dir / "view.off");
    EXPECT_GT(viewed.size(), 100u);
    EXPECT_EQ(viewed, bytes(dir / "render.off"));  // the same exact result, written the same way
    const std::string viewedSampled = bytes(dir / "sampled.off");
    EXPECT_GT(viewedSampled.size(), 100u);
    EXPECT_EQ(viewedSampled, bytes(dir / "render-sampled.off"));
    // A bad name is the script's error, naming the command.
    const ProcessResult bad = view(scene, "size 64 64\nexport nowhere/x.stl\n");
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_TRUE(bad.err.find("nowhere/x.stl: cannot write") != std::string::npos) << bad.err;
}

TEST_F(StrataView, AFlatModelExportsTheDrawingsStrataRenderWrites) {
    // The panel and the scripts offer SVG and DXF for a 2D model; the
    // export writes the drawing strata-render writes, byte for byte.
    const std::string scene = dir.write("flat.csg", "difference() {\n  square(size = [6, 4], center = false);\n"
                                                    "  circle($fn = 24, r = 1);\n}\n");
    const ProcessResult r = view(scene, "size 64 64\nexport view.svg\nexport view.dxf\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    for (const auto& [viewedName, renderedName] : {std::pair{"view.svg", "render.svg"}, std::pair{"view.dxf", "render.dxf"}}) {
        const std::string rendered = dir / renderedName;
        const ProcessResult cli = runProcess({kRender, scene, "--export", rendered});
        ASSERT_EQ(cli.exitCode, 0) << cli.err;
        const std::string viewed = bytes(dir / viewedName);
        EXPECT_GT(viewed.size(), 100u) << viewedName;
        EXPECT_EQ(viewed, bytes(rendered)) << viewedName;
    }
    // A mesh of a 2D model is the export's error, as strata-render's.
    const ProcessResult mesh = view(scene, "size 64 64\nexport flat.stl\n");
    EXPECT_EQ(mesh.exitCode, 1);
    EXPECT_NE(mesh.err.find("a 2D model has no solid to export"), std::string::npos) << mesh.err;
}

TEST_F(StrataView, OpensScadThroughOpenscad) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    const std::string scad = dir.write("a.scad", "difference() { cube(10, center = true); sphere(6.5, $fn = 48); }\n");
    const ProcessResult r = view(scad, "size 320 240\ncamera 0,0,0,60,0,30,80\nscreenshot scad.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(runProcess({"/bin/sh", "-c", "openscad -o '" + (dir / "a.csg") + "' '" + scad + "'"}).exitCode, 0);
    expectSameAsRender(readPng(dir / "scad.png"), render(dir / "a.csg", {"--camera=0,0,0,60,0,30,80"}));
}

TEST_F(StrataView, ASavedUseOrIncludeFileReloadsTheScad) {
    // OpenSCAD's -d list names the files a .scad uses, includes and imports;
    // saving one of them reloads the model, as OpenSCAD's automatic reload does.
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    dir.write("parts lib.scad", "module part() { cube(8, center = true); }\n");
    dir.write("second lib.scad", "module part() { sphere(5, $fn = 24); }\n");
    dir.write("size.scad", "height = 4;\n");
    dir.write("taller.scad", "height = 12;\n");
    const std::string scad = dir.write("a.scad", "use <parts lib.scad>\ninclude <size.scad>\npart();\n"
                                                 "translate([12, 0, 0]) cube([3, 3, height]);\n");
    const ProcessResult r = view(scad,
                                 "size 320 240\n"
                                 "camera 0,0,0,60,0,30,90\n"
                                 "screenshot first.png\n"
                                 "copy \"second lib.scad\" \"parts lib.scad\"\n"
                                 "wait-reload\n"
                                 "screenshot used.png\n"
                                 "copy taller.scad size.scad\n"
                                 "wait-reload\n"
                                 "screenshot included.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string camera = "--camera=0,0,0,60,0,30,90";
    const Image first = readPng(dir / "first.png"), used = readPng(dir / "used.png");
    const Image included = readPng(dir / "included.png");
    expectSameAsRender(included, render(scad, {camera}));
    EXPECT_GT(differingPixels(first, used), 100);
    EXPECT_GT(differingPixels(used, included), 100);
}

TEST_F(StrataView, EscCancelsALoadButNeverQuitsAndCtrlQQuits) {
    // A save that makes the model slow to load (the exact hull of a
    // difference: seconds); Esc while it loads cancels it and keeps the
    // last good model, Esc with nothing running does nothing, Ctrl+Q ends
    // the session before the next command.
    const std::string a = dir.write("a.csg", kScene);
    dir.write("slow.csg", "hull() {\n\tdifference() {\n\t\tsphere($fn = 200, $fa = 12, $fs = 2, r = 10);\n"
                          "\t\tcube(size = [10, 10, 10], center = false);\n\t}\n}\n");
    const ProcessResult r = view(a, "size 64 64\ncopy slow.csg a.csg\nwait-loading\nkey escape\nwait-reload\nprint console\n"
                                    "key escape\nprint title\nkey ctrl+q\nscreenshot after-quit.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(a + ": loading cancelled\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("strata-view: " + a + "\n"), std::string::npos) << r.out;  // still there after the idle Esc
    EXPECT_FALSE(std::filesystem::exists(dir / "after-quit.png"));
}

// An exact Minkowski sum of non-convex parts (found by the geometry fuzzer):
// its load takes about 50 s here in a release build, far longer under ASan.
const std::string kMinutesToLoad =
    "minkowski() {\n"
    "sphere($fn = 7, $fa = 12, $fs = 2, r = 10);\n"
    "intersection() {\n"
    "linear_extrude(height = 1.5, center = false, twist = 3, slices = 2, scale = -1) {\n"
    "hull() {\n"
    "polygon(points = [[8, 2], [0, 6], [6, 6]], paths = undef, convexity = 1);\n"
    "square(size = [2, 1], center = true);\n"
    "}\n"
    "}\n"
    "}\n"
    "rotate_extrude(angle = 270, $fn = 8) {\n"
    "multmatrix([[1, 0, 0, 9], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
    "square(size = [2, 1], center = true);\n"
    "}\n"
    "}\n"
    "}\n";

TEST_F(StrataView, ASlowFirstLoadOpensTheWindowAtOnce) {
    if (runProcess({"/bin/sh", "-c", "command -v xwininfo"}).exitCode != 0) GTEST_SKIP() << "xwininfo not installed";
    // No script: a user's session. The window must be there within 15 s while
    // the model takes most of a minute to load; then the session is killed.
    const std::string slow = dir.write("slow.csg", kMinutesToLoad);
    const std::string shell =
        "'" + std::string(kView) + "' '" + slow + "' --imgsize 320,240 & pid=$!\n"
        "i=0\n"
        "while [ $i -lt 150 ]; do\n"
        "  if xwininfo -root -tree 2>/dev/null | grep -q 'strata-view: .*slow.csg'; then kill -9 $pid; echo shown; exit 0; fi\n"
        "  if ! kill -0 $pid 2>/dev/null; then echo exited; exit 1; fi\n"
        "  sleep 0.1; i=$((i + 1))\n"
        "done\n"
        "kill -9 $pid; echo 'no window'; exit 1\n";
    const ProcessResult r = runProcess({"/bin/sh", "-c", shell});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_EQ(r.out, "shown\n") << r.err;
}

TEST_F(StrataView, OpenedFilesAreKeptAsRecentFilesNewestFirst) {
    const std::string a = dir.write("a.csg", kScene), b = dir.write("b.csg", kScene);
    const ProcessResult first = view(a, "size 32 32\nopen b.csg\nopen a.csg\nopen b.csg\nprint recent\n");
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_EQ(first.out, b + "\n" + a + "\n");
    // Kept for the next session, in the state folder; a file gone since stays
    // listed (the panel greys it).
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "state/strata/recent-files"));
    std::filesystem::remove(b);
    const ProcessResult second = view(a, "size 32 32\nprint recent\n");
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_EQ(second.out, a + "\n" + b + "\n");
}

TEST_F(StrataView, AScadsMessagesNameItsLines) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    // OpenSCAD exports this; strata refuses the open polyhedron, at its line in
    // the .scad (the first line of the export).
    const std::string scad = dir.write("open.scad", "\n\n// three lines down\npolyhedron(points = [[0, 0, 0], [1, 0, 0], "
                                                    "[0, 1, 0]], faces = [[0, 1, 2]]);\n");
    const ProcessResult r = runProcess({kView, scad}, {{"DISPLAY", ":4999"}});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(r.err.starts_with(scad + ":4:1: polyhedron is not a closed solid")) << r.err;
}

TEST_F(StrataView, TreeRowsNameTheScadLinesOfTheirCalls) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    dir.write("parts.scad", "module peg() {\n  cylinder(r = 1, h = 4);\n}\n");
    const std::string scad = dir.write("a.scad", "use <parts.scad>\n\ntranslate([20, 0, 0]) sphere(3);\npeg();\n");
    const ProcessResult r = view(scad, "size 64 64\nprint tree\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(\d+ sphere \(line 3\)\n)"))) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(\d+ cylinder \(parts\.scad line 2\)\n)"))) << r.out;
}

// The line of `text` numbered `number` (from 1); empty past the end.
std::string lineOf(const std::string& text, int number) {
    std::istringstream in(text);
    std::string line;
    for (int k = 1; std::getline(in, line); ++k)
        if (k == number) return line;
    return {};
}

// The "(CSG line N)" of the first `print tree` row whose label is `label`; 0 when none.
int csgLineOfRow(const std::string& out, const std::string& label) {
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, std::regex(R"(\s*\d+ )" + label + R"( \(CSG line (\d+)\))")))
            return std::stoi(m[1].str());
    }
    return 0;
}

TEST_F(StrataView, SaveCsgWritesTheExportWhoseLinesTheTreeNames) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    // The sphere and the cube land on different lines of the export (2 and 4),
    // neither of them the .scad's line. Each name is called twice in the
    // .scad, so neither node can be traced to its call, and the rows name
    // the export's lines.
    const std::string scad = dir.write("a.scad", "echo(\"two solids\");\n\ntranslate([20, 0, 0]) sphere(3);\ncube(5);\n"
                                                 "if (false) { sphere(1); cube(1); }\n");
    const ProcessResult r = view(scad, "size 64 64\nprint tree\nsave-csg out.csg\nprint console\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The file is OpenSCAD's export, byte for byte, and strata-render reads it.
    ASSERT_EQ(runProcess({"/bin/sh", "-c", "openscad -o '" + (dir / "by-openscad.csg") + "' '" + scad + "'"}).exitCode, 0);
    std::ifstream saved(dir / "out.csg", std::ios::binary), exported(dir / "by-openscad.csg", std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(saved), std::istreambuf_iterator<char>()};
    const std::string byOpenscad{std::istreambuf_iterator<char>(exported), std::istreambuf_iterator<char>()};
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text, byOpenscad);
    const ProcessResult stats = runProcess({kRender, dir / "out.csg", "--imgsize", "32,32", "-o", dir / "out.png", "--stats"});
    EXPECT_EQ(stats.exitCode, 0) << stats.err;
    // The tree's rows name the lines of the saved file where their statements are.
    const int cube = csgLineOfRow(r.out, "cube"), sphere = csgLineOfRow(r.out, "sphere");
    ASSERT_GT(cube, 0) << r.out;
    ASSERT_GT(sphere, 0) << r.out;
    EXPECT_NE(cube, sphere);
    EXPECT_TRUE(lineOf(text, cube).find("cube(") != std::string::npos) << cube << "\n" << text;
    EXPECT_TRUE(lineOf(text, sphere).find("sphere(") != std::string::npos) << sphere << "\n" << text;
    // The console says where it went and what its lines are.
    EXPECT_NE(r.out.find("saved the CSG export of " + scad + " to " + (dir / "out.csg") +
                         ": the positions in messages and the tree's CSG lines are its lines\n"),
              std::string::npos)
        << r.out;
}

TEST_F(StrataView, SaveCsgWithoutAnExportOrIntoAMissingFolderIsOneLineAndNoFile) {
    const std::string csg = dir.write("a.csg", kScene);
    const ProcessResult plain = view(csg, "size 32 32\nsave-csg out.csg\n");
    EXPECT_EQ(plain.exitCode, 1);
    EXPECT_EQ(lineCount(plain.err), 1) << plain.err;
    EXPECT_TRUE(plain.err.starts_with(dir / "script.txt:2:1: cannot save a CSG export: " + csg + " is not a .scad"))
        << plain.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csg"));
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    const std::string scad = dir.write("b.scad", "cube(5);\n");
    const ProcessResult missing = view(scad, "size 32 32\nsave-csg nowhere/out.csg\n");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_EQ(lineCount(missing.err), 1) << missing.err;
    EXPECT_TRUE(missing.err.starts_with(dir / "script.txt:2:1: " + (dir / "nowhere/out.csg") + ": cannot write"))
        << missing.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "nowhere"));
}

TEST_F(StrataView, ThePanelIsDockedBesideTheViewAndFramingFramesWhatIsSeen) {
    const std::string scene = dir.write("a.csg", kScene);
    const std::string script = dir / "script.txt";
    std::ofstream(script) << "view-all\nscreenshot docked.png\npanel off\nview-all\nscreenshot whole.png\n";
    const ProcessResult r = runProcess({kView, scene, "--imgsize", "1000,600", "--script", script});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image docked = readPng(dir / "docked.png"), whole = readPng(dir / "whole.png");
    // With the panel, the view is what the panel leaves of the window, and the
    // model is fitted into it; without, the view is the whole window.
    EXPECT_EQ(whole.width, 1000);
    EXPECT_EQ(docked.height, 600);
    EXPECT_GT(docked.width, 500);
    EXPECT_LT(docked.width, 800);
    EXPECT_GT(drawnPixels(docked), 1000);
}

// The drawn pixels' box: {left, top, right, bottom}, or all -1 when none.
std::array<int, 4> drawnBox(const Image& image) {
    std::array<int, 4> box{-1, -1, -1, -1};
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const unsigned char* p = pixelAt(image, x, y);
            if (std::equal(p, p + 4, image.rgba.begin())) continue;
            if (box[0] < 0 || x < box[0]) box[0] = x;
            if (box[1] < 0) box[1] = y;
            box[2] = std::max(box[2], x);
            box[3] = y;
        }
    }
    return box;
}

TEST_F(StrataView, ViewAllAndResetFitTheModelBesideAPanelOfAnyWidth) {
    // A long bar: fitted to the whole window it would run under the panel.
    const std::string scene = dir.write("bar.csg", "cube(size = [60, 6, 6], center = true);\n");
    const ProcessResult r = runProcess({kView, scene, "--imgsize", "1000,600", "--script",
                                        dir.write("s.txt", "panel 260\nview-all\nscreenshot narrow.png\nkey r\nscreenshot narrow-reset.png\n"
                                                           "panel 480\nview-all\nscreenshot wide.png\nkey r\nscreenshot wide-reset.png\n")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const auto& [name, width] : std::vector<std::pair<std::string, int>>{
             {"narrow.png", 740}, {"narrow-reset.png", 740}, {"wide.png", 520}, {"wide-reset.png", 520}}) {
        const Image shot = readPng(dir / name);
        // The view is what the panel leaves of the window, and the whole bar
        // is inside it, clear of its edges.
        EXPECT_EQ(shot.width, width) << name;
        const std::array<int, 4> box = drawnBox(shot);
        EXPECT_GT(box[0], 2) << name;
        EXPECT_GT(box[1], 2) << name;
        EXPECT_LT(box[2], shot.width - 3) << name;
        EXPECT_LT(box[3], shot.height - 3) << name;
        EXPECT_GT(box[2] - box[0], shot.width / 3) << name << ": the bar is fitted, not lost in the view";
    }
}

TEST_F(StrataView, ThePanelsTextFitsItsDefaultAndItsNarrowestWidth) {
    // Long words where the panel shows names and messages: the file (its
    // path, the open section's list, the recent files, the export field),
    // an error naming it, the tree, a sampled export's row, fixed layers.
    const std::string name = "a_model_whose_name_is_far_longer_than_any_panel_is_wide_at_first.csg";
    const std::string scene = dir.write(name, kScene);
    dir.write("bad.csg", kScene + "frobnicate(a_parameter_with_a_long_name = 12345678901234567890);\n");
    const ProcessResult r = runProcess({kView, scene, "--imgsize", "640,900", "--script", dir.write("s.txt",
                                 "panel open\n"
                                 "panel export\n"
                                 "export-sampled out.stl\n"
                                 "layers 3\n"
                                 "print panel\n"
                                 "copy bad.csg " + name + "\n"
                                 "wait-reload\n"
                                 "print error\n"
                                 "print panel\n"
                                 "panel 220\n"
                                 "print panel\n"
                                 "screenshot narrow.png\n")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(name + ":9:1: unknown module 'frobnicate'"), std::string::npos) << r.out;
    const std::string fits = "the panel's text fits its width\n";
    std::size_t at = 0;
    for (int k = 0; k < 3; ++k) {
        at = r.out.find(fits, at);
        ASSERT_NE(at, std::string::npos) << "check " << k << ":\n" << r.out;
        at += fits.size();
    }
    EXPECT_EQ(r.out.find("passes the panel's right edge"), std::string::npos) << r.out;
    EXPECT_EQ(readPng(dir / "narrow.png").width, 640 - 220);  // the panel did narrow, the view took the rest
}

TEST_F(StrataView, AScriptsSizeIsTheViewsWithThePanelBesideIt) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene,
                                 "size 200 150\n"
                                 "screenshot view.png\n"
                                 "screenshot-window docked.png\n"
                                 "panel off\n"
                                 "screenshot-window alone.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image shot = readPng(dir / "view.png"), docked = readPng(dir / "docked.png"),
                alone = readPng(dir / "alone.png");
    ASSERT_EQ(shot.width, 200);
    ASSERT_EQ(shot.height, 150);
    EXPECT_GT(drawnPixels(shot), 1000);
    // The window holds the panel (340 units, a pixel each on Xvfb) and the
    // whole view right of it; without the panel, the view alone.
    ASSERT_EQ(docked.width, 340 + 200);
    ASSERT_EQ(docked.height, 150);
    EXPECT_EQ(alone.width, 200);
    EXPECT_EQ(alone.height, 150);
    int differing = 0;
    for (int y = 0; y < 150; ++y)
        for (int x = 0; x < 200; ++x)
            differing += !std::equal(pixelAt(shot, x, y), pixelAt(shot, x, y) + 3, pixelAt(docked, 340 + x, y));
    EXPECT_EQ(differing, 0) << "pixels of the view that the window does not show as they are";
}

TEST_F(StrataView, ConsoleShowsOpenscadsEchoAndAStaleModelSaysSoInTheTitle) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    const std::string scad = dir.write("a.scad", "echo(\"hello from the model\");\ncube(5);\n");
    dir.write("broken.scad", "cube(5)\nsphere(;\n");
    const ProcessResult r = view(scad,
                                 "size 64 64\n"
                                 "panel off\n"
                                 "print console\n"
                                 "print title\n"
                                 "copy broken.scad a.scad\n"
                                 "wait-reload\n"
                                 "print title\n"
                                 "print console\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // OpenSCAD's ECHO line, as OpenSCAD prints it, before the reload.
    const std::size_t echo = r.out.find("ECHO: \"hello from the model\"\n");
    EXPECT_NE(echo, std::string::npos) << r.out;
    // With the panel hidden, the title tells that the model shown is stale, and the console has the error.
    EXPECT_NE(r.out.find("strata-view: " + scad + "\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("strata-view: " + scad + "  [error: showing the last good version]\n"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.rfind(scad + ":"), std::string::npos) << r.out;
}

// Seen from the top, orthographic, 100 away: 240 / (2 * 100 * tan(11.25 deg))
// = 6.03 pixels per unit, the origin at the image's centre, X to the right,
// Y up. A block at x, y in [5, 9] stays off the axes; one at x in [-2, 2],
// y in [10, 14] lies over the Y axis.
const std::string kAxesScene = R"(
multmatrix([[1, 0, 0, 5], [0, 1, 0, 5], [0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = [4, 4, 4], center = false); }
multmatrix([[1, 0, 0, -2], [0, 1, 0, 10], [0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = [4, 4, 4], center = false); }
)";

TEST_F(StrataView, AxesScaleMarkersAndTheCornerCrossAreDrawnOverTheModel) {
    const std::string scene = dir.write("axes.csg", kAxesScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "projection o\n"
                                 "camera 0,0,100,0,0,0\n"
                                 "screenshot off.png\n"
                                 "show axes on\n"
                                 "screenshot axes.png\n"
                                 "show scale on\n"
                                 "screenshot scale.png\n"
                                 "show axes off\n"
                                 "screenshot off-again.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image off = readPng(dir / "off.png"), axes = readPng(dir / "axes.png"), scale = readPng(dir / "scale.png");
    ASSERT_EQ(axes.width, 320);
    expectSameAsRender(off, render(scene, {"--camera=0,0,100,0,0,0", "--projection", "o"}));
    EXPECT_EQ(differingPixels(off, readPng(dir / "off-again.png")), 0);  // off is off
    // The positive X axis: the row through the centre, black (Cornfield's axes colour).
    auto black = [](const Image& image, int x, int y) { return isRgb(image, x, y, 0, 0, 0); };
    int onAxis = 0;
    for (int x = 166; x < 316; ++x) onAxis += black(axes, x, 119) || black(axes, x, 120);
    EXPECT_GE(onAxis, 148);
    for (int x = 166; x < 316; ++x) EXPECT_FALSE(black(off, x, 119) || black(off, x, 120)) << x;
    // The negative half is dashed: about half of it drawn.
    int dashes = 0;
    for (int x = 10; x < 150; ++x) dashes += black(axes, x, 119) || black(axes, x, 120);
    EXPECT_GT(dashes, 40);
    EXPECT_LT(dashes, 100);
    // The Y axis shows below the second block and is hidden by it (y in [10, 14]: rows 36 to 60).
    int visibleY = 0, hiddenY = 0;
    for (int y = 70; y < 110; ++y) visibleY += black(axes, 159, y) || black(axes, 160, y);
    for (int y = 40; y < 56; ++y) hiddenY += black(axes, 159, y) || black(axes, 160, y);
    EXPECT_GE(visibleY, 38);
    EXPECT_EQ(hiddenY, 0);
    // A scale marker at x = 10 (every 10 at distance 100), 100 / 60 long towards -Y: down.
    auto tickAt = [&](const Image& image) {
        int n = 0;
        for (int x = 218; x <= 223; ++x) n += black(image, x, 125);
        return n;
    };
    EXPECT_GE(tickAt(scale), 1);
    EXPECT_EQ(tickAt(axes), 0);
    // The corner cross: its red X axis right of (32, 216).
    int red = 0;
    for (int x = 34; x < 44; ++x)
        for (int y = 213; y < 219; ++y) red += isRgb(axes, x, y, 255, 0, 0);
    EXPECT_GE(red, 8);
    for (int x = 34; x < 44; ++x)
        for (int y = 213; y < 219; ++y) EXPECT_FALSE(isRgb(off, x, y, 255, 0, 0));
}

// The numbers beside the scale markers, found where a closed-form projection
// of their ticks puts them. Seen from the top at distance 100: ticks every 10,
// and as 100 is under three times 10^2, every second tick numbered: 20, 40,
// ... The characters are u / 2 wide on a pitch of 3u / 4 and lie u / 4 to 5u / 4
// from the axis, u = 100 / 60: X's on the +Y side (up in the image), the
// first character from the origin centred on its tick.
TEST_F(StrataView, ScaleNumbersStandBesideTheirTicks) {
    const std::string scene = dir.write("axes.csg", kAxesScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "projection o\n"
                                 "camera 0,0,100,0,0,0\n"
                                 "show axes on\n"
                                 "screenshot axes.png\n"
                                 "show scale on\n"
                                 "screenshot scale.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image axes = readPng(dir / "axes.png"), scale = readPng(dir / "scale.png");
    ASSERT_EQ(scale.width, 320);
    const double pixelsPerUnit = 240.0 / (2.0 * 100.0 * std::tan(11.25 * 3.14159265358979323846 / 180.0));
    const double u = 100.0 / 60.0;
    // Black pixels in the image of x in [x0, x1], y in [u / 4, 5u / 4], one pixel of slack around.
    auto blackIn = [&](const Image& image, double x0, double x1) {
        const int c0 = static_cast<int>(std::floor(160.0 + x0 * pixelsPerUnit)) - 1;
        const int c1 = static_cast<int>(std::floor(160.0 + x1 * pixelsPerUnit)) + 1;
        const int r0 = static_cast<int>(std::floor(120.0 - 1.25 * u * pixelsPerUnit)) - 1;
        const int r1 = static_cast<int>(std::floor(120.0 - 0.25 * u * pixelsPerUnit)) + 1;
        EXPECT_LT(r1, 119);  // clear of the axis itself
        int n = 0;
        for (int y = r0; y <= r1; ++y)
            for (int x = c0; x <= c1; ++x) n += isRgb(image, x, y, 0, 0, 0);
        return n;
    };
    // "20": '2' centred on x = 20, '0' on 20 + 3u / 4.
    const double twentyFrom = 20.0 - u / 4.0, twentyTo = 20.0 + 0.75 * u + u / 4.0;
    EXPECT_GE(blackIn(scale, twentyFrom, twentyTo), 20);
    EXPECT_EQ(blackIn(axes, twentyFrom, twentyTo), 0);
    // "-20" reads along +X: "0" on x = -20, then "2" and "-" further out.
    const double minusFrom = -20.0 - 1.5 * u - u / 4.0, minusTo = -20.0 + u / 4.0;
    EXPECT_GE(blackIn(scale, minusFrom, minusTo), 25);
    EXPECT_EQ(blackIn(axes, minusFrom, minusTo), 0);
    // No number at 10, an odd tick.
    EXPECT_EQ(blackIn(scale, 10.0 - u / 4.0, 10.0 + 0.75 * u + u / 4.0), 0);
}

TEST_F(StrataView, EdgesShowOnTheVisibleSurfacesOnly) {
    const std::string scene = dir.write("cube.csg", "cube(size = [10, 10, 10], center = true);\n");
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "screenshot plain.png\n"
                                 "show edges on\n"
                                 "screenshot edges.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image plain = readPng(dir / "plain.png"), edges = readPng(dir / "edges.png");
    ASSERT_EQ(plain.width, edges.width);
    // Edge pixels: lighter than the face beneath, and only where the cube is
    // or right beside it (a silhouette's edge drawn whole).
    auto background = [&](int x, int y) {
        const unsigned char* p = pixelAt(plain, x, y);
        return std::equal(p, p + 4, plain.rgba.data());
    };
    int lighter = 0, awayFromTheCube = 0;
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x) {
            const unsigned char *a = pixelAt(plain, x, y), *b = pixelAt(edges, x, y);
            if (std::equal(a, a + 4, b)) continue;
            if (background(x, y)) {
                bool besideTheCube = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = std::clamp(x + dx, 0, plain.width - 1), ny = std::clamp(y + dy, 0, plain.height - 1);
                        besideTheCube = besideTheCube || !background(nx, ny);
                    }
                awayFromTheCube += !besideTheCube;
            } else if (b[0] >= a[0] && b[1] >= a[1] && b[2] >= a[2]) {
                ++lighter;
            }
        }
    EXPECT_EQ(awayFromTheCube, 0);
    // The three visible faces' sides and diagonals, some 9 segments of 50 to 100 pixels.
    EXPECT_GT(lighter, 300);
}

// A cube turned 30 degrees about Z, seen from the top (orthographic, 100
// away, 240 / (2 * 100 * tan(11.25 deg)) pixels per unit): the outline of its
// top face is its silhouette. Each column along the two shallow sides (slope
// tan 30 deg, one pixel per column) has an edge pixel within a row of where
// the side's closed-form projection crosses it, whichever side of the
// silhouette that pixel's centre falls on.
TEST_F(StrataView, EdgesAtASilhouetteAreDrawnWhole) {
    const std::string scene =
        dir.write("turned.csg",
                  "multmatrix([[0.8660254037844387, -0.5, 0, 0], [0.5, 0.8660254037844387, 0, 0], "
                  "[0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = [10, 10, 10], center = true); }\n");
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "projection o\n"
                                 "camera 0,0,100,0,0,0\n"
                                 "screenshot plain.png\n"
                                 "show edges on\n"
                                 "screenshot edges.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image plain = readPng(dir / "plain.png"), edges = readPng(dir / "edges.png");
    ASSERT_EQ(plain.width, 320);
    ASSERT_EQ(edges.width, 320);
    const double pixelsPerUnit = 240.0 / (2.0 * 100.0 * std::tan(11.25 * 3.14159265358979323846 / 180.0));
    const double c = std::sqrt(3.0) / 2.0, s = 0.5;
    // The top corner (x, y) turned, in pixels: column and row coordinates (rows from the top).
    auto corner = [&](double x, double y) {
        return std::pair<double, double>(160.0 + (c * x - s * y) * pixelsPerUnit, 120.0 - (s * x + c * y) * pixelsPerUnit);
    };
    auto changed = [&](int x, int y) {
        const unsigned char *a = pixelAt(plain, x, y), *b = pixelAt(edges, x, y);
        return !std::equal(a, a + 4, b);
    };
    int columns = 0, missing = 0, outside = 0;
    for (const auto& [from, to] : {std::pair(corner(-5, 5), corner(5, 5)), std::pair(corner(-5, -5), corner(5, -5))}) {
        for (int x = static_cast<int>(std::ceil(from.first)) + 3; x <= static_cast<int>(std::floor(to.first)) - 3; ++x) {
            const double t = (x + 0.5 - from.first) / (to.first - from.first);
            const int row = static_cast<int>(std::floor(from.second + t * (to.second - from.second)));
            bool found = false;
            for (int y = row - 1; y <= row + 1; ++y) {
                found = found || changed(x, y);
                const unsigned char* p = pixelAt(plain, x, y);
                outside += changed(x, y) && std::equal(p, p + 4, plain.rgba.data());
            }
            ++columns;
            missing += !found;
        }
    }
    EXPECT_GT(columns, 70);
    EXPECT_EQ(missing, 0);
    // Some of them lie just outside, on the background.
    EXPECT_GT(outside, 10);
}

// The debug views that show the camera's view (depth, normal, forms) get the
// lines too; the depth and normal views, black where nothing is hit, draw
// the axes light grey. The peel grid's small images get none.
TEST_F(StrataView, DebugViewsShowTheAxesAndEdges) {
    const std::string scene = dir.write("axes.csg", kAxesScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "projection o\n"
                                 "camera 0,0,100,0,0,0\n"
                                 "debug normal\n"
                                 "screenshot normal.png\n"
                                 "debug depth\n"
                                 "screenshot depth.png\n"
                                 "show axes on\n"
                                 "screenshot depth-axes.png\n"
                                 "debug normal\n"
                                 "screenshot normal-axes.png\n"
                                 "debug forms\n"
                                 "screenshot forms-axes.png\n"
                                 "show axes off\n"
                                 "debug peel\n"
                                 "screenshot peel.png\n"
                                 "show axes on\n"
                                 "show edges on\n"
                                 "screenshot peel-lines.png\n"
                                 "debug normal\n"
                                 "show axes off\n"
                                 "screenshot normal-edges.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image depth = readPng(dir / "depth.png");
    ASSERT_EQ(depth.width, 320);
    // The positive X axis, the row through the centre (see kAxesScene).
    auto onXAxis = [](const Image& image, int r, int g, int b) {
        int n = 0;
        for (int x = 166; x < 316; ++x) n += isRgb(image, x, 119, r, g, b) || isRgb(image, x, 120, r, g, b);
        return n;
    };
    EXPECT_EQ(onXAxis(depth, 0xe5, 0xe5, 0xe5), 0);
    EXPECT_GE(onXAxis(readPng(dir / "depth-axes.png"), 0xe5, 0xe5, 0xe5), 148);
    EXPECT_GE(onXAxis(readPng(dir / "normal-axes.png"), 0xe5, 0xe5, 0xe5), 148);
    EXPECT_GE(onXAxis(readPng(dir / "forms-axes.png"), 0, 0, 0), 148);  // the scheme's (Cornfield: black)
    EXPECT_EQ(differingPixels(readPng(dir / "peel.png"), readPng(dir / "peel-lines.png")), 0);
    // Edges over the normal view (the tops: (0.5, 0.5, 1)): lighter, on the
    // blocks only (x, y in [5, 9]: columns 190 to 214, rows 66 to 90; x in
    // [-2, 2], y in [10, 14]: columns 148 to 172, rows 36 to 60), a pixel of slack.
    const Image normal = readPng(dir / "normal.png"), edges = readPng(dir / "normal-edges.png");
    ASSERT_EQ(normal.width, 320);
    int lighter = 0, elsewhere = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x) {
            const unsigned char *a = pixelAt(normal, x, y), *b = pixelAt(edges, x, y);
            if (std::equal(a, a + 4, b)) continue;
            const bool onBlock = (x >= 188 && x <= 216 && y >= 64 && y <= 92) || (x >= 145 && x <= 175 && y >= 34 && y <= 62);
            if (!onBlock) ++elsewhere;
            else if (b[0] > a[0]) ++lighter;
        }
    EXPECT_EQ(elsewhere, 0);
    EXPECT_GT(lighter, 50);
}

TEST_F(StrataView, ADeletedFileKeepsTheModelAndSaysSo) {
    const std::string scene = dir.write("a.csg", kScene);
    dir.write("b.csg", kNoCylinder);
    // Each sleep lets the loop poll the file once more (every 200 ms).
    const ProcessResult r = view(scene,
                                 "size 160 120\n"
                                 "screenshot before.png\n"
                                 "remove a.csg\n"
                                 "sleep 250\nsleep 250\nsleep 250\nsleep 250\n"
                                 "print title\n"
                                 "print console\n"
                                 "screenshot gone.png\n"
                                 "copy b.csg a.csg\n"
                                 "wait-reload\n"
                                 "print title\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("strata-view: " + scene + "  [deleted: showing the last good version]\n"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(scene + ": the file is gone; showing the last good version"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find(scene + ": the file is gone"), std::string::npos) << r.err;
    // Back: reloaded, the title plain again.
    EXPECT_TRUE(r.out.ends_with("strata-view: " + scene + "\n")) << r.out;
    const Image before = readPng(dir / "before.png");
    EXPECT_GT(drawnPixels(before), 1000);
    EXPECT_EQ(differingPixels(before, readPng(dir / "gone.png")), 0);
}

// The red line of a stale model lies over the debug views as over the shaded
// one: the window's bottom rows hold its red text (255, 90, 90).
TEST_F(StrataView, AStaleModelsRedLineStaysInsideTheViewBesideThePanel) {
    // With the panel shown, the red line lies over the 3D view alone, wrapped
    // to its width: none of its red left of the view's first column.
    const std::string scene = dir.write("a.csg", kScene);
    dir.write("broken.csg", "cube(size = [1, 1, 1]);\nsphere(r = );\n");
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "copy broken.csg a.csg\n"
                                 "wait-reload\n"
                                 "screenshot-window stale.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image window = readPng(dir / "stale.png");
    const int viewLeft = window.width - 320;
    ASSERT_GT(viewLeft, 100);  // the panel is shown
    int inside = 0, outside = 0;
    for (int y = std::max(0, window.height - 40); y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) (x < viewLeft ? outside : inside) += isRgb(window, x, y, 255, 90, 90);
    EXPECT_GT(inside, 30);
    EXPECT_EQ(outside, 0);
}

TEST_F(StrataView, AStaleModelsRedLineShowsOverTheDebugViews) {
    const std::string scene = dir.write("a.csg", kScene);
    const ProcessResult r = view(scene,
                                 "size 320 240\n"
                                 "panel off\n"
                                 "debug depth\n"
                                 "screenshot-window fresh.png\n"
                                 "remove a.csg\n"
                                 "sleep 250\nsleep 250\nsleep 250\nsleep 250\n"
                                 "screenshot-window depth.png\n"
                                 "debug peel\n"
                                 "screenshot-window peel.png\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto redInTheBottomRows = [](const Image& image) {
        int n = 0;
        for (int y = std::max(0, image.height - 30); y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) n += isRgb(image, x, y, 255, 90, 90);
        return n;
    };
    const Image fresh = readPng(dir / "fresh.png");
    ASSERT_EQ(fresh.width, 320);
    EXPECT_EQ(redInTheBottomRows(fresh), 0);
    EXPECT_GT(redInTheBottomRows(readPng(dir / "depth.png")), 30);
    EXPECT_GT(redInTheBottomRows(readPng(dir / "peel.png")), 30);
}

// A screenshot as the very first command, window and all just made: never
// an empty (black) image. Each run is a new process: only a session's first
// frame can show it.
TEST_F(StrataView, AFirstCommandScreenshotIsNeverBlack) {
    const std::string scene = dir.write("a.csg", kScene);
    constexpr int kRuns = 50;
    int black = 0;
    for (int run = 0; run < kRuns; ++run) {
        const std::string shot = "first-" + std::to_string(run) + ".png";
        const ProcessResult r = view(scene, "screenshot " + shot + "\n");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image image = readPng(dir / shot);
        ASSERT_GT(image.width, 0);
        bool allBlack = true;
        for (std::size_t k = 0; k < image.rgba.size() && allBlack; k += 4)
            allBlack = image.rgba[k] == 0 && image.rgba[k + 1] == 0 && image.rgba[k + 2] == 0;
        black += allBlack;
        EXPECT_GT(drawnPixels(image), 1000) << shot;
    }
    EXPECT_EQ(black, 0);
}

}  // namespace
