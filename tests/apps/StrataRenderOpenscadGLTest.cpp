// strata-render with OpenSCAD's command line: a .scad with -D, through the
// installed openscad, renders pixel for pixel as its CSG export made by
// `openscad -D ... -o x.csg`, relative imports resolve from the .scad's
// folder, strata-bench times a .scad with -D like any scene file, and
// OpenSCAD's --viewall, --autocenter and --preview name what strata-render
// draws anyway, and `--light openscad --no-outline` gives the colours of
// OpenSCAD's own preview image. The .scad tests are skipped where openscad is
// not installed (scripts/deps.sh installs it), the preview comparison also
// where there is no X display for OpenSCAD's window.

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kRender = STRATA_RENDER_EXE;
const std::string kBench = STRATA_BENCH_EXE;
const std::string kRow = (std::filesystem::path(STRATA_TEST_DIR) / "data" / "scad" / "holed_row.scad").string();

bool haveOpenscad() { return runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode == 0; }

// The PNG's RGBA bytes (opaque where it has no alpha, as OpenSCAD's images);
// empty when it cannot be read.
std::vector<unsigned char> readRgba(const std::string& path, int& w, int& h) {
    std::vector<unsigned char> rgba;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return rgba;
    w = in->spec().width;
    h = in->spec().height;
    const int channels = in->spec().nchannels;
    if (channels != 3 && channels != 4) return rgba;
    const std::size_t pixels = static_cast<std::size_t>(w) * h;
    std::vector<unsigned char> read(pixels * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, read.data())) return rgba;
    rgba.assign(pixels * 4, 255);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < channels; ++c) rgba[i * 4 + c] = read[i * channels + c];
    return rgba;
}

// How two RGB(A) images of one size compare: `face` counts the pixels inside a
// flat face of `reference` (a pixel not of `background` whose eight
// neighbours all have its colour), `faceOff` those of them where `image`
// differs by more than `levels` in a channel; `off` the same over every pixel.
struct ColourAgreement {
    std::size_t pixels = 0, off = 0, face = 0, faceOff = 0;
};

ColourAgreement compareColours(const std::vector<unsigned char>& reference, const std::vector<unsigned char>& image,
                               int w, int h, const unsigned char background[3], int levels) {
    ColourAgreement a;
    auto at = [&](const std::vector<unsigned char>& rgba, int x, int y, int c) {
        return static_cast<int>(rgba[(static_cast<std::size_t>(y) * w + x) * 4 + c]);
    };
    auto same = [&](int x0, int y0, int x1, int y1) {
        for (int c = 0; c < 3; ++c)
            if (at(reference, x0, y0, c) != at(reference, x1, y1, c)) return false;
        return true;
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool off = false;
            for (int c = 0; c < 3; ++c) off = off || std::abs(at(reference, x, y, c) - at(image, x, y, c)) > levels;
            ++a.pixels;
            a.off += off ? 1 : 0;
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1) continue;
            bool isBackground = true;
            for (int c = 0; c < 3; ++c) isBackground = isBackground && at(reference, x, y, c) == background[c];
            if (isBackground) continue;
            bool flat = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) flat = flat && same(x, y, x + dx, y + dy);
            if (!flat) continue;
            ++a.face;
            a.faceOff += off ? 1 : 0;
        }
    }
    return a;
}

}  // namespace

TEST(StrataRenderOpenscadGL, OpenscadLightGivesTheColoursOfOpenscadsPreview) {
    if (!haveOpenscad()) GTEST_SKIP() << "openscad not installed";
    if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no X display for openscad --preview";
    TempDir dir;
    // Own faces in the scheme's colour, cut faces in its cut colour, a leaf's
    // own color(), faces at many angles: every kind of base colour the shade
    // pass lights.
    const std::string scad = dir.write("part.scad",
                                       "difference() { cube(10, center = true); sphere(6.5); }\n"
                                       "translate([12, 0, 0]) color([0.2, 0.4, 0.9]) cylinder(r = 3, h = 8, center = true);\n");
    const unsigned char background[3] = {255, 255, 229};  // Cornfield's
    struct View {
        std::string camera, projection;
    };
    for (const View& view : {View{"0,0,0,55,0,25,60", "o"}, View{"3,0,0,60,0,35,70", "p"}}) {
        SCOPED_TRACE(view.camera + " " + view.projection);
        const std::vector<std::string> common{"--imgsize=200,150", "--camera=" + view.camera,
                                              "--projection=" + view.projection};
        std::vector<std::string> openscad{"/usr/bin/env", "openscad", "--preview", "-o", dir / "openscad.png"};
        openscad.insert(openscad.end(), common.begin(), common.end());
        openscad.push_back(scad);
        const ProcessResult os = runProcess(openscad);
        ASSERT_EQ(os.exitCode, 0) << os.err;
        for (const bool openscadLook : {true, false}) {
            std::vector<std::string> strata{kRender, scad, "-q", "-o", dir / "strata.png"};
            strata.insert(strata.end(), common.begin(), common.end());
            if (openscadLook) strata.insert(strata.end(), {"--light", "openscad", "--no-outline"});
            const ProcessResult r = runProcess(strata);
            ASSERT_EQ(r.exitCode, 0) << r.err;
            int w = 0, h = 0, sw = 0, sh = 0;
            const std::vector<unsigned char> reference = readRgba(dir / "openscad.png", w, h);
            const std::vector<unsigned char> image = readRgba(dir / "strata.png", sw, sh);
            ASSERT_EQ(w, 200);
            ASSERT_EQ(h, 150);
            ASSERT_EQ(sw, w);
            ASSERT_EQ(sh, h);
            const ColourAgreement a = compareColours(reference, image, w, h, background, 3);
            ASSERT_GT(a.face, 1500u) << a.face << " pixels inside faces: the model should fill a good part of the image";
            if (openscadLook) {
                // Inside faces every pixel; over the whole image only where a
                // silhouette or crease is rasterized a pixel apart.
                EXPECT_EQ(a.faceOff, 0u) << "of " << a.face << " pixels inside faces";
                EXPECT_LE(a.off * 100, a.pixels) << a.off << " of " << a.pixels << " pixels";
            } else {
                // strata's own light and outline: the comparison tells them apart.
                EXPECT_GT(a.faceOff * 2, a.face) << "of " << a.face << " pixels inside faces";
            }
        }
    }
}

TEST(StrataRenderOpenscadGL, AScadWithDefinesRendersAsItsCsgExport) {
    if (!haveOpenscad()) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    // Three cubes 5 wide instead of the file's two 4 wide; the default view
    // fits either, so a -D that did not arrive shows in the image.
    const std::vector<std::string> defines{"-D", "count=3", "-D", "size=5"};
    std::vector<std::string> scad{kRender, kRow, "-o", dir / "scad.png", "--imgsize", "96,64"};
    scad.insert(scad.begin() + 2, defines.begin(), defines.end());
    const ProcessResult r = runProcess(scad);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");

    std::vector<std::string> exportArgs{"/usr/bin/env", "openscad", "-o", dir / "row.csg"};
    exportArgs.insert(exportArgs.end(), defines.begin(), defines.end());
    exportArgs.push_back(kRow);
    ASSERT_EQ(runProcess(exportArgs).exitCode, 0);
    const ProcessResult csg = runProcess({kRender, dir / "row.csg", "-o", dir / "csg.png", "--imgsize", "96,64"});
    ASSERT_EQ(csg.exitCode, 0) << csg.err;
    // And without the definitions: another image.
    ASSERT_EQ(runProcess({kRender, kRow, "-o", dir / "plain.png", "--imgsize", "96,64"}).exitCode, 0);

    int w = 0, h = 0, cw = 0, ch = 0, pw = 0, ph = 0;
    const std::vector<unsigned char> fromScad = readRgba(dir / "scad.png", w, h);
    const std::vector<unsigned char> fromCsg = readRgba(dir / "csg.png", cw, ch);
    const std::vector<unsigned char> plain = readRgba(dir / "plain.png", pw, ph);
    ASSERT_EQ(w, 96);
    ASSERT_EQ(h, 64);
    ASSERT_EQ(cw, w);
    ASSERT_EQ(ch, h);
    ASSERT_EQ(fromScad.size(), fromCsg.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < fromScad.size(); ++i) differing += fromScad[i] != fromCsg[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << "bytes differing between the .scad and its CSG export";
    EXPECT_NE(plain, fromScad) << "-D changed nothing";
}

TEST(StrataRenderOpenscadGL, EchoLinesComeAfterTheOutputsAndQuietDropsThem) {
    if (!haveOpenscad()) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    const std::string scad = dir.write("echo.scad", "n = 1;\necho(n = n);\ncube(n);\n");
    const ProcessResult r = runProcess({kRender, scad, "-D", "n=2", "-o", dir / "a.png", "--imgsize", "16,16"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "ECHO: n = 2\n");
    const ProcessResult q = runProcess({kRender, scad, "-q", "-o", dir / "b.png", "--imgsize", "16,16"});
    ASSERT_EQ(q.exitCode, 0) << q.err;
    EXPECT_EQ(q.err, "");
}

TEST(StrataRenderOpenscadGL, RelativeImportsResolveFromTheScadsFolder) {
    if (!haveOpenscad()) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    std::filesystem::create_directories(dir / "model");
    std::filesystem::copy_file(std::filesystem::path(STRATA_TEST_DIR) / "data" / "meshes" / "cube.off",
                               dir / "model/cube.off");
    const std::string scad = dir.write("model/part.scad", "difference() { import(\"cube.off\"); sphere(0.6); }\n");
    // The test runs in another folder: only the .scad's own makes cube.off found.
    const ProcessResult r = runProcess({kRender, scad, "-o", dir / "part.png", "--imgsize", "32,32"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "part.png"));
}

TEST(StrataBenchGL, TimesAScadWithDefines) {
    if (!haveOpenscad()) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    const std::string json = dir / "bench.json";
    const ProcessResult r = runProcess({kBench, "--files", kRow, "-D", "count=3", "--size", "32x32", "--frames", "1",
                                        "--warmup", "0", "--no-opencsg", "--json", json});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(json);
    std::stringstream data;
    data << in.rdbuf();
    EXPECT_NE(data.str().find(R"("scene": "holed_row.scad")"), std::string::npos) << data.str();
    EXPECT_NE(data.str().find(R"("k": 6)"), std::string::npos) << "three cubes, three holes:\n" << data.str();
}

TEST(StrataRenderOpenscadGL, ViewallAutocenterAndPreviewNameTheDefaultView) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", "cube(size = [3, 2, 1]);\n");
    ASSERT_EQ(runProcess({kRender, scene, "-o", dir / "plain.png", "--imgsize", "48,32"}).exitCode, 0);
    const ProcessResult r = runProcess(
        {kRender, scene, "--viewall", "--autocenter", "--preview", "-o", dir / "openscad.png", "--imgsize", "48,32"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    int w = 0, h = 0;
    EXPECT_EQ(readRgba(dir / "openscad.png", w, h), readRgba(dir / "plain.png", w, h));
    EXPECT_EQ(w, 48);
}

TEST(StrataBenchGL, DefinesWithoutAScadAreAUsageError) {
    const std::string csg = (std::filesystem::path(STRATA_TEST_DIR).parent_path() / "examples" / "gear.csg").string();
    const ProcessResult r = runProcess({kBench, "--files", csg, "-D", "n=1", "--no-opencsg"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "strata-bench: -D: only a .scad scene takes definitions (the scene is '" + csg + "')\n");
    EXPECT_EQ(r.out, "");
}

TEST(StrataRenderOpenscadGL, QuietLeavesOnlyErrorsOnStderr) {
    TempDir dir;
    const std::string scene = dir.write("roof.csg", "roof() square(1);\ncube(1);\n");
    const ProcessResult r = runProcess({kRender, scene, "-o", dir / "a.png", "--imgsize", "16,16"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("warning: 'roof' is not supported"), std::string::npos) << r.err;
    const ProcessResult q = runProcess({kRender, scene, "--quiet", "-o", dir / "b.png", "--imgsize", "16,16"});
    ASSERT_EQ(q.exitCode, 0) << q.err;
    EXPECT_EQ(q.err, "");
}
