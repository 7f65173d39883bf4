// strata-render end to end: a cube, checked pixel by pixel against a ray-box
// intersection worked out here from CONTRACT.md's camera formulas.
//
//        z (up)
//        |   cube [-1,1]^3
//        |  +---+
//   eye  |  |   |      eye (0,-10,0) looks along +y at the origin:
//   ---->+--|---|--> y f = (0,1,0), r = (1,0,0), u = (0,0,1);
//           +---+      the front face y = -1 is 9 units deep.

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::lineCount;
using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kExe = STRATA_RENDER_EXE;

struct Vec {
    double x, y, z;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec normalize(Vec a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

struct Hit {
    double depth;  // dot(P - E, f)
    Vec normal;
};

// Slab test of the ray against the box [-1,1]^3; the entry face gives the normal.
std::optional<Hit> hitCube(Vec origin, Vec dir, Vec f, Vec eye) {
    double tNear = -std::numeric_limits<double>::infinity(), tFar = std::numeric_limits<double>::infinity();
    Vec normal{0, 0, 0};
    const double o[3] = {origin.x, origin.y, origin.z}, d[3] = {dir.x, dir.y, dir.z};
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(d[axis]) < 1e-15) {
            if (std::abs(o[axis]) > 1) return std::nullopt;
            continue;
        }
        double t0 = (-1 - o[axis]) / d[axis], t1 = (1 - o[axis]) / d[axis];
        double sign = -1;  // entering through the -axis face
        if (t0 > t1) {
            std::swap(t0, t1);
            sign = 1;
        }
        if (t0 > tNear) {
            tNear = t0;
            normal = Vec{0, 0, 0};
            (axis == 0 ? normal.x : axis == 1 ? normal.y : normal.z) = sign;
        }
        tFar = std::min(tFar, t1);
    }
    if (tNear > tFar || tNear <= 0) return std::nullopt;
    const Vec p = origin + tNear * dir;
    return Hit{dot(p + (-1.0) * eye, f), normal};
}

struct Expected {
    std::optional<Hit> hit;
    bool interior = false;  // the whole pixel sees the same face (or nothing): safe to compare
};

// The contract's camera for eye (0,-10,0), center 0: every ray of pixel (i,j)
// at sub-pixel offset (di,dj) from its centre.
std::optional<Hit> castPixel(double i, double j, int w, int h, bool ortho) {
    const Vec eye{0, -10, 0}, f{0, 1, 0}, r{1, 0, 0}, u{0, 0, 1};
    const double t = std::tan(22.5 / 2 * std::numbers::pi / 180), a = double(w) / h;
    const double x = 2 * (i + 0.5) / w - 1, y = 1 - 2 * (j + 0.5) / h;
    if (ortho) {
        const double hh = 10 * t;
        return hitCube(eye + (x * hh * a) * r + (y * hh) * u, f, f, eye);
    }
    return hitCube(eye, normalize(f + (x * t * a) * r + (y * t) * u), f, eye);
}

Expected expectedAt(int i, int j, int w, int h, bool ortho) {
    Expected e;
    e.hit = castPixel(i, j, w, h, ortho);
    e.interior = true;
    for (double di : {-0.5, 0.5})
        for (double dj : {-0.5, 0.5}) {
            const auto corner = castPixel(i + di, j + dj, w, h, ortho);
            if (corner.has_value() != e.hit.has_value() ||
                (corner && dot(corner->normal, e.hit->normal) < 0.5))
                e.interior = false;
        }
    return e;
}

std::vector<float> readExr(const std::string& path, int& w, int& h, std::vector<std::string>& channels) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const auto& spec = in->spec();
    w = spec.width;
    h = spec.height;
    channels.assign(spec.channelnames.begin(), spec.channelnames.end());
    std::vector<float> pixels(static_cast<std::size_t>(w) * h * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
    return pixels;
}

void checkCube(bool ortho, const std::vector<std::string>& extraArgs) {
    TempDir dir;
    constexpr int kW = 65, kH = 49;  // odd: the centre pixel's ray is the view axis
    const std::string scene = dir.write("cube.csg", "cube(size = [2, 2, 2], center = true);\n");
    std::vector<std::string> argv{kExe, scene, "-o", dir / "cube.png", "--depth", dir / "z.exr",
                                  "--normal", dir / "n.exr", "--stats"};
    argv.insert(argv.end(), extraArgs.begin(), extraArgs.end());
    if (ortho) argv.insert(argv.end(), {"--projection", "o"});
    const ProcessResult r = runProcess(argv);
    ASSERT_EQ(r.exitCode, 0) << r.err;

    int w = 0, h = 0;
    std::vector<std::string> channels;
    const std::vector<float> depth = readExr(dir / "z.exr", w, h, channels);
    ASSERT_EQ(w, kW);
    ASSERT_EQ(h, kH);
    ASSERT_EQ(channels, std::vector<std::string>{"Z"});
    const std::vector<float> normal = readExr(dir / "n.exr", w, h, channels);
    ASSERT_EQ(channels, (std::vector<std::string>{"R", "G", "B"}));

    // The centre pixel looks straight at the front face.
    const int centre = (kH / 2) * kW + kW / 2;
    EXPECT_NEAR(depth[centre], 9.0, 1e-4);
    EXPECT_NEAR(normal[centre * 3 + 1], -1.0, 1e-4);

    std::size_t covered = 0, boundary = 0, compared = 0;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            const Expected e = expectedAt(i, j, kW, kH, ortho);
            covered += e.hit.has_value();
            if (!e.interior) {
                ++boundary;
                continue;
            }
            ++compared;
            const int k = j * kW + i;
            if (!e.hit) {
                EXPECT_TRUE(std::isinf(depth[k]) && depth[k] > 0) << i << "," << j << ": " << depth[k];
                EXPECT_EQ(normal[k * 3 + 0], 0.0f);
                EXPECT_EQ(normal[k * 3 + 1], 0.0f);
                EXPECT_EQ(normal[k * 3 + 2], 0.0f);
                continue;
            }
            // |dz| <= 1e-4 of the cube's diagonal (2*sqrt(3)), as the accuracy suite demands.
            EXPECT_NEAR(depth[k], e.hit->depth, 1e-4 * 2 * std::sqrt(3.0)) << i << "," << j;
            EXPECT_NEAR(normal[k * 3 + 0], e.hit->normal.x, 1e-3) << i << "," << j;
            EXPECT_NEAR(normal[k * 3 + 1], e.hit->normal.y, 1e-3) << i << "," << j;
            EXPECT_NEAR(normal[k * 3 + 2], e.hit->normal.z, 1e-3) << i << "," << j;
        }
    EXPECT_GT(compared, boundary);  // the test really compared most of the image

    // --stats: one JSON object on stdout, with the covered pixel count.
    ASSERT_FALSE(r.out.empty());
    EXPECT_EQ(r.out.front(), '{');
    const std::size_t at = r.out.find("\"covered_pixels\": ");
    ASSERT_NE(at, std::string::npos) << r.out;
    const long reported = std::stol(r.out.substr(at + 18));
    EXPECT_LE(std::labs(reported - static_cast<long>(covered)), static_cast<long>(boundary)) << r.out;

    // The PNG: right size, opaque where the cube is, and not the background colour there.
    auto png = OIIO::ImageInput::open(dir / "cube.png");
    ASSERT_TRUE(png);
    EXPECT_EQ(png->spec().width, kW);
    EXPECT_EQ(png->spec().height, kH);
    EXPECT_EQ(png->spec().nchannels, 4);
    std::vector<unsigned char> rgba(static_cast<std::size_t>(kW) * kH * 4);
    png->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, rgba.data());
    EXPECT_EQ(rgba[centre * 4 + 3], 255);
    const bool differs = rgba[centre * 4 + 0] != rgba[0] || rgba[centre * 4 + 1] != rgba[1] ||
                         rgba[centre * 4 + 2] != rgba[2] || rgba[centre * 4 + 3] != rgba[3];
    EXPECT_TRUE(differs) << "the cube's centre has the corner's colour";
}

}  // namespace

TEST(StrataRenderGL, CubeDepthNormalAndCoverageMatchThePerspectiveContract) {
    checkCube(false, {"--camera", "0,-10,0,0,0,0", "--imgsize", "65,49"});
}

TEST(StrataRenderGL, CubeDepthNormalAndCoverageMatchTheOrthographicContract) {
    checkCube(true, {"--camera=0,-10,0,0,0,0", "--imgsize=65,49"});  // the --opt=value form
}

TEST(StrataRenderGL, DefaultViewRendersAMeshFileWithAFittedCamera) {
    TempDir dir;
    // A unit cube as OFF, faces counter-clockwise seen from outside.
    const std::string mesh = dir.write("cube.off",
                                       "OFF\n8 6 0\n"
                                       "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                       "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 3 7 6 2\n4 0 4 7 3\n4 1 2 6 5\n");
    const ProcessResult r = runProcess({kExe, mesh, "--imgsize", "64,64", "--depth", dir / "z.exr", "--stats"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    int w = 0, h = 0;
    std::vector<std::string> channels;
    const std::vector<float> depth = readExr(dir / "z.exr", w, h, channels);
    ASSERT_EQ(w, 64);
    // The fitted view centres the model: the centre pixels see it, the corners do not.
    const float c = depth[32 * 64 + 32];
    EXPECT_TRUE(std::isfinite(c)) << c;
    EXPECT_TRUE(std::isinf(depth[0]));
    EXPECT_TRUE(std::isinf(depth[64 * 64 - 1]));
}

TEST(StrataRenderGL, ReferenceFlagGivesTheSameContractImagesFromTheCpuRayCaster) {
    checkCube(false, {"--camera", "0,-10,0,0,0,0", "--imgsize", "65,49", "--reference"});
    checkCube(true, {"--camera", "0,-10,0,0,0,0", "--imgsize", "65,49", "--reference"});
}

// Every bundled example renders headless, warns about nothing, and shows the
// model: its centre region is covered and the image's border is background
// (the fitted default view frames the whole model).
TEST(StrataRenderGL, EveryBundledExampleRendersAndIsFramedByTheDefaultView) {
    const std::filesystem::path examples = std::filesystem::path(STRATA_TEST_DIR).parent_path() / "examples";
    int rendered = 0;
    for (const auto& entry : std::filesystem::directory_iterator(examples)) {
        if (entry.path().extension() != ".csg") continue;
        SCOPED_TRACE(entry.path().string());
        TempDir dir;
        const ProcessResult r = runProcess(
            {kExe, entry.path().string(), "--imgsize", "96,72", "-o", dir / "x.png", "--depth", dir / "z.exr"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err, "") << "examples should parse without warnings";
        int w = 0, h = 0;
        std::vector<std::string> channels;
        const std::vector<float> depth = readExr(dir / "z.exr", w, h, channels);
        ASSERT_EQ(w, 96);
        ASSERT_EQ(h, 72);
        std::size_t covered = 0, borderCovered = 0;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const bool hit = std::isfinite(depth[static_cast<std::size_t>(j) * w + i]);
                covered += hit;
                if (hit && (i == 0 || j == 0 || i == w - 1 || j == h - 1)) ++borderCovered;
            }
        EXPECT_GT(covered, static_cast<std::size_t>(w * h / 50)) << "the model covers at least 2% of the image";
        EXPECT_EQ(borderCovered, 0u);
        ++rendered;
    }
    EXPECT_GE(rendered, 5);
}

// A union of 4096 cubes, a 16 x 16 x 16 grid, as OpenSCAD exports one
// (a multmatrix() around each cube): seen from outside, the tree is a
// union of leaves, drawn plainly (depth-tested, no peel). The depth must be
// the CPU reference's.
TEST(StrataRenderGL, AUnionOfThousandsOfCubesIsDrawnPlainlyAndTheReferencesSurface) {
    TempDir dir;
    {
        std::ofstream csg(dir / "cubes.csg");
        csg << "union() {\n";
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j)
                for (int k = 0; k < 16; ++k)
                    csg << "multmatrix([[1, 0, 0, " << 1.5 * i << "], [0, 1, 0, " << 1.5 * j << "], [0, 0, 1, "
                        << 1.5 * k << "], [0, 0, 0, 1]]) { cube(size = [1, 1, 1], center = false); }\n";
        csg << "}\n";
    }
    const ProcessResult gpu = runProcess({kExe, dir / "cubes.csg", "--imgsize", "160,120", "--depth", dir / "gpu.exr",
                                          "--stats"});
    ASSERT_EQ(gpu.exitCode, 0) << gpu.err;
    // A union seen from outside: its leaves drawn depth-tested (PlainPass.h).
    EXPECT_NE(gpu.out.find("\"plain_frame\": true,"), std::string::npos) << gpu.out.substr(0, 1200);
    EXPECT_NE(gpu.out.find("\"leaves\": 4096,"), std::string::npos);
    const ProcessResult cpu = runProcess(
        {kExe, dir / "cubes.csg", "--imgsize", "160,120", "--depth", dir / "cpu.exr", "--reference"});
    ASSERT_EQ(cpu.exitCode, 0) << cpu.err;
    int w = 0, h = 0;
    std::vector<std::string> channels;
    const std::vector<float> a = readExr(dir / "gpu.exr", w, h, channels);
    const std::vector<float> b = readExr(dir / "cpu.exr", w, h, channels);
    ASSERT_EQ(a.size(), b.size());
    std::size_t covered = 0, coverageDiffers = 0, depthDiffers = 0;
    for (std::size_t p = 0; p < a.size(); ++p) {
        const bool ha = std::isfinite(a[p]), hb = std::isfinite(b[p]);
        if (ha != hb) {
            ++coverageDiffers;
        } else if (ha) {
            ++covered;
            depthDiffers += std::abs(a[p] - b[p]) > 1e-4f * b[p] ? 1 : 0;
        }
    }
    EXPECT_GT(covered, a.size() / 4);
    // Silhouette pixels, a ray grazing an edge, may differ; a whole cube may not.
    EXPECT_LE(coverageDiffers, a.size() / 500);
    EXPECT_LE(depthDiffers, covered / 100);
}

// A full disk: a file-size limit (ulimit -f) fails the writes as ENOSPC
// would (with EFBIG): one line naming the output, status 1, no file left.
TEST(StrataRenderGL, AFullDiskIsOneLineAndLeavesNoFile) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", "sphere($fn = 64, r = 5);\n");
    // 4 blocks (2 KiB in dash's 512-byte blocks): less than a 256 x 256 PNG of a sphere.
    const ProcessResult r = runProcess(
        {"/bin/sh", "-c", "ulimit -f 4 && exec \"$0\" \"$1\" -o \"$2\" --imgsize 256,256", kExe, scene, dir / "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind((dir / "out.png") + ": cannot write PNG (File too large)", 0), 0u) << r.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"cube.csg"});
}

// SIGTERM at any moment of a run (loading, rendering, writing) leaves
// either no output or the whole output, and never a temporary.
TEST(StrataRenderGL, ATerminatedRunLeavesNoTemporary) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", "sphere($fn = 64, r = 5);\n");
    for (const char* delay : {"0.05", "0.2", "0.35", "0.5", "0.8"}) {
        const ProcessResult r = runProcess({"/bin/sh", "-c",
                                            "\"$0\" \"$1\" -o \"$2\" --depth \"$3\" --imgsize 512,512 & "
                                            "sleep $4; kill -TERM $! 2>/dev/null; wait $!; exit 0",
                                            kExe, scene, dir / "out.png", dir / "z.exr", delay});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        for (const std::string& name : dir.files()) {
            EXPECT_TRUE(name == "cube.csg" || name == "out.png" || name == "z.exr") << "left behind: " << name;
        }
        std::filesystem::remove(dir / "out.png");
        std::filesystem::remove(dir / "z.exr");
    }
}

// An image too large for the memory the process may use: one line saying
// so, not a GL error from an engine source line.
TEST(StrataRenderGL, AnImageTooLargeForMemoryIsOneLine) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#else
    TempDir dir;
    const std::string scene = dir.write("cube.csg", "cube(size = 1);\n");
    const ProcessResult r = runProcess({"/bin/sh", "-c", "ulimit -v 3000000 && exec \"$0\" \"$1\" -o \"$2\" --imgsize 16384,16384",
                                        kExe, scene, dir / "big.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("renderer: not enough memory for a 16384 x 16384 image (its targets take 7424 MiB)", 0), 0u)
        << r.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"cube.csg"});
#endif
}

// An address-space limit too small for the GL driver: llvmpipe printed its
// own warnings and no context at 300 MB, hung at 430 MB and aborted in LLVM
// at 450 MB. Each is now the out-of-memory line (gpu::Context reserves the
// driver's room before asking for it). `timeout` keeps a hang from stalling
// the suite.
TEST(StrataRenderGL, AnAddressSpaceLimitTooSmallForTheDriverIsOneLine) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#else
    TempDir dir;
    const std::string scene = dir.write("cube.csg", "cube(size = 1);\n");
    for (const char* limit : {"300000", "430000", "450000"}) {
        const ProcessResult r = runProcess({"/bin/sh", "-c", std::string("ulimit -v ") + limit +
                                                                 " && exec timeout 120 \"$0\" \"$1\" -o \"$2\"",
                                            kExe, scene, dir / "cube.png"});
        EXPECT_EQ(r.exitCode, 1) << limit << ": " << r.err;
        EXPECT_EQ(r.err, scene + ": out of memory (the scene needs more memory than the process may use)\n") << limit;
        EXPECT_EQ(dir.files(), std::vector<std::string>{"cube.csg"}) << limit;
    }
#endif
}

// A translucent color() against OpenSCAD 2021.01's own preview of the same
// scene (tests/data/openscad-alpha/README.md): OpenSCAD lights surfaces
// otherwise, so only what does not depend on the light is compared. The
// leaves are pure red, so in the green and blue channels a pixel holds only
// the background's share, (1 - a) over one layer, (1 - a)^2 over two.
TEST(StrataRenderGL, TranslucentColoursLetTheBackgroundThroughAsOpenScadsPreview) {
    const std::filesystem::path data = std::filesystem::path(STRATA_TEST_DIR) / "data" / "openscad-alpha";
    auto readPng = [](const std::string& path, int& w, int& h) {
        std::vector<unsigned char> rgb;
        auto in = OIIO::ImageInput::open(path);
        if (!in) return rgb;
        w = in->spec().width;
        h = in->spec().height;
        rgb.resize(static_cast<std::size_t>(w) * h * 3);
        in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data());
        return rgb;
    };
    for (const char* name : {"lone", "in-front", "product", "cut"}) {
        int ow = 0, oh = 0;
        const std::vector<unsigned char> openscad = readPng(data / (std::string(name) + ".png"), ow, oh);
        ASSERT_EQ(ow, 64) << name;
        ASSERT_EQ(oh, 48) << name;
        for (const bool reference : {false, true}) {
            TempDir dir;
            std::vector<std::string> argv{kExe, data / (std::string(name) + ".csg"), "-o", dir / "out.png",
                                          "--imgsize", "64,48", "--projection", "o", "--camera", "0,-100,0,0,0,0"};
            if (reference) argv.push_back("--reference");
            const ProcessResult r = runProcess(argv);
            ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
            int w = 0, h = 0;
            const std::vector<unsigned char> strata = readPng(dir / "out.png", w, h);
            ASSERT_EQ(w, 64);
            ASSERT_EQ(h, 48);
            // The 4 x 4 pixels around the centre, inside the red surface in both.
            for (int j = 22; j < 26; ++j)
                for (int i = 30; i < 34; ++i) {
                    const std::size_t k = (static_cast<std::size_t>(j) * 64 + i) * 3;
                    EXPECT_GT(openscad[k], 150) << name << " " << i << "," << j;  // red: the leaf is there
                    for (int c : {1, 2})
                        EXPECT_NEAR(int(strata[k + c]), int(openscad[k + c]), 2)
                            << name << (reference ? " --reference " : " ") << i << "," << j << " channel " << c;
                }
        }
    }
}

namespace {

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

// Several scenes in one process: each writes, byte for byte, what a process
// of its own writes (the renderer and its shaders carry over, nothing of the
// scene before does), under the name that %s gives it.
TEST(StrataRenderGL, SeveralScenesInOneProcessRenderAsEachAlone) {
    const std::filesystem::path examples = std::filesystem::path(STRATA_TEST_DIR).parent_path() / "examples";
    TempDir dir;
    // A CSG tree, a mesh file, then a union (a plain frame) after them.
    const std::string unionScene =
        dir.write("pair.csg", "cube(size = 2);\nmultmatrix([[1, 0, 0, 3], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(r = 1);\n");
    const std::vector<std::string> scenes{(examples / "gear.csg").string(), (examples / "meshes" / "twisted_star.stl").string(),
                                          unionScene};
    std::vector<std::string> batch{kExe};
    batch.insert(batch.end(), scenes.begin(), scenes.end());
    batch.insert(batch.end(), {"-o", dir / "%s.png", "--depth", dir / "%s-z.exr", "--imgsize", "80,60"});
    const ProcessResult r = runProcess(batch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    for (const std::string& scene : scenes) {
        const std::string name = std::filesystem::path(scene).stem().string();
        SCOPED_TRACE(name);
        const ProcessResult alone = runProcess({kExe, scene, "-o", dir / "alone.png", "--depth", dir / "alone-z.exr",
                                                "--imgsize", "80,60"});
        ASSERT_EQ(alone.exitCode, 0) << alone.err;
        const std::string png = fileBytes(dir / (name + ".png")), z = fileBytes(dir / (name + "-z.exr"));
        EXPECT_GT(png.size(), 100u);
        EXPECT_EQ(png, fileBytes(dir / "alone.png"));
        EXPECT_EQ(z, fileBytes(dir / "alone-z.exr"));
    }
}

// A scene that fails in a batch says its one line and writes nothing; the
// others are written, and the run ends with a count and exit status 1.
TEST(StrataRenderGL, ABatchGoesOnPastABadSceneAndCountsTheFailures) {
    TempDir dir;
    const std::string good = dir.write("good.csg", "cube(1);\n");
    const std::string bad = dir.write("bad.csg", "cube(\n");
    const std::string other = dir.write("other.csg", "sphere(1);\n");
    const ProcessResult r =
        runProcess({kExe, good, bad, other, "-o", dir / "out-%s.png", "--imgsize", "32,24"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 2) << r.err;
    EXPECT_TRUE(r.err.starts_with(bad + ":2:1: ")) << r.err;
    EXPECT_NE(r.err.find("strata-render: 1 of 3 scenes failed\n"), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "out-good.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "out-other.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out-bad.png"));
}
