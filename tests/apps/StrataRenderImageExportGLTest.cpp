// strata-render --export --export-sampled (the image-space export), run as a user runs it.
// The exported mesh is read and checked by CGAL, not by strata: closed,
// outward, free of self-intersections; its volume against CGAL's exact
// result of the same scene (--export-exact) and converging as the
// resolution grows; sharp corners where the solid has them; a torus's
// genus; and, rendered by strata as a plain mesh, the same depth image as
// the CSG scene's to within a cell.

#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>
#include <cmath>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::lineCount;
using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Solid = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

const std::string kExe = STRATA_RENDER_EXE;

Solid read(const std::string& path) {
    Solid s;
    EXPECT_TRUE(CGAL::IO::read_polygon_mesh(path, s)) << path;
    return s;
}

// What CGAL says of a mesh that an export must be.
void expectSound(const Solid& s, const std::string& what) {
    ASSERT_FALSE(s.is_empty()) << what;
    EXPECT_TRUE(s.is_valid()) << what;
    EXPECT_TRUE(CGAL::is_closed(s)) << what;
    EXPECT_TRUE(CGAL::is_triangle_mesh(s)) << what;
    EXPECT_TRUE(PMP::is_outward_oriented(s)) << what;
    EXPECT_FALSE(PMP::does_self_intersect(s)) << what;
    for (const auto f : s.faces()) {
        const auto h = s.halfedge(f);
        const Kernel::Point_3& a = s.point(s.source(h));
        const Kernel::Point_3& b = s.point(s.target(h));
        const Kernel::Point_3& c = s.point(s.target(s.next(h)));
        ASSERT_FALSE(CGAL::collinear(a, b, c)) << what << ": a degenerate triangle";
    }
}

std::string exportMesh(const TempDir& dir, const std::string& scene, const std::string& name,
                       std::vector<std::string> extra = {}) {
    const std::string out = dir / name;
    // Sampled unless the exact result is asked for, to compare with.
    const bool exact = std::find(extra.begin(), extra.end(), "--export-exact") != extra.end();
    std::vector<std::string> argv{kExe, scene, "--export", out};
    if (!exact) argv.push_back("--export-sampled");
    argv.insert(argv.end(), extra.begin(), extra.end());
    const ProcessResult r = runProcess(argv);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    // Nothing on stderr but progress lines (a slow build, under the
    // sanitizers, runs long enough to print them).
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);) {
        EXPECT_TRUE(std::regex_match(line, std::regex(R"(strata-render: .*: \d+ of \d+ \(.*\))"))) << line;
    }
    return out;
}

const char* kCubeMinusSphere =
    "difference() { cube(size = [20, 20, 20], center = true); "
    "multmatrix([[1,0,0,6],[0,1,0,5],[0,0,1,7],[0,0,0,1]]) sphere(r = 9, $fn = 40); }\n";

TEST(StrataRenderImageExport, VolumeConvergesToTheExactResult) {
    TempDir dir;
    const std::string scene = dir.write("cut.csg", kCubeMinusSphere);
    const double exact = PMP::volume(read(exportMesh(dir, scene, "exact.off", {"--export-exact"})));
    double previous = 1e300;
    for (int resolution : {24, 48, 96}) {
        const std::string name = "r" + std::to_string(resolution) + ".off";
        const Solid s = read(exportMesh(dir, scene, name, {"--export-resolution", std::to_string(resolution)}));
        expectSound(s, name);
        const double error = std::fabs(PMP::volume(s) - exact) / exact;
        // A cell of 20 / resolution; the cut sphere's faces are planar
        // facets the contouring meets only at the crossings it sees.
        EXPECT_LT(error, 0.03 / resolution) << name;
        EXPECT_LT(error, previous) << name;
        previous = error;
        std::printf("resolution %d: volume off by %.2e of %.1f\n", resolution, error, exact);
    }
}

TEST(StrataRenderImageExport, KeepsTheCornersOfATurnedBlock) {
    TempDir dir;
    // A block turned by odd angles: no face on a grid plane, every corner
    // a sharp feature.
    const double c = std::cos(0.4), s = std::sin(0.4), c2 = std::cos(0.7), s2 = std::sin(0.7);
    char m[400];
    std::snprintf(m, sizeof m, "multmatrix([[%.17g,%.17g,0,0.3],[%.17g,%.17g,0,0.2],[0,0,1,0.1],[0,0,0,1]]) "
                  "multmatrix([[1,0,0,0],[0,%.17g,%.17g,0],[0,%.17g,%.17g,0],[0,0,0,1]]) "
                  "cube(size = [7, 5, 3], center = true);\n", c, -s, s, c, c2, -s2, s2, c2);
    const std::string scene = dir.write("block.csg", m);
    const Solid mesh = read(exportMesh(dir, scene, "block.off", {"--export-resolution", "32"}));
    expectSound(mesh, "block");
    const Solid exact = read(exportMesh(dir, scene, "exact.off", {"--export-exact"}));
    int corners = 0;
    for (const auto v : exact.vertices()) {
        double nearest = 1e300;
        for (const auto w : mesh.vertices())
            nearest = std::min(nearest, std::sqrt(CGAL::squared_distance(exact.point(v), mesh.point(w))));
        EXPECT_LT(nearest, 1e-4) << "a corner of the block is lost";
        ++corners;
    }
    EXPECT_EQ(corners, 8);
    EXPECT_NEAR(PMP::volume(mesh), 7.0 * 5.0 * 3.0, 1e-3);
}

TEST(StrataRenderImageExport, ATorusHasGenusOne) {
    TempDir dir;
    const std::string scene =
        dir.write("torus.csg", "rotate_extrude($fn = 48) multmatrix([[1,0,0,10],[0,1,0,0],[0,0,1,0],[0,0,0,1]]) "
                               "circle(r = 3, $fn = 24);\n");
    const Solid mesh = read(exportMesh(dir, scene, "torus.off", {"--export-resolution", "64"}));
    expectSound(mesh, "torus");
    const long euler = static_cast<long>(mesh.number_of_vertices()) - static_cast<long>(mesh.number_of_edges()) +
                       static_cast<long>(mesh.number_of_faces());
    EXPECT_EQ(euler, 0);
    std::vector<std::size_t> component(mesh.number_of_faces());
    auto map = CGAL::make_property_map(component);
    EXPECT_EQ(PMP::connected_components(mesh, map), 1u);
}

TEST(StrataRenderImageExport, GpuAndReferenceSamplesGiveOneMesh) {
    TempDir dir;
    const std::string scene = dir.write("cut.csg", kCubeMinusSphere);
    const Solid gpu = read(exportMesh(dir, scene, "gpu.off", {"--export-resolution", "40"}));
    const Solid cpu = read(exportMesh(dir, scene, "cpu.off", {"--export-resolution", "40", "--reference"}));
    expectSound(gpu, "gpu");
    expectSound(cpu, "reference");
    EXPECT_NEAR(PMP::volume(gpu), PMP::volume(cpu), 1e-4 * PMP::volume(cpu));
    // The same contour; the flat regions' merge may take a few vertices
    // differently where the GPU's single-precision crossings sit a little
    // off a plane that the reference's lie on.
    EXPECT_NEAR(double(gpu.number_of_faces()), double(cpu.number_of_faces()), 0.01 * double(cpu.number_of_faces()));
}

// OpenSCAD's logo at the default 512 cells, where its sphere's and
// cylinders' facets span tens of cells: the GPU's crossings lie off their
// planes by a float's rounding, and near a ridge between two facets some
// name the facet across it. Each takes the plane it lies on, so the GPU's
// mesh merges as far as the reference's, to within a few per cent (before,
// it kept 1.8 times its triangles), and both are clean.
TEST(StrataRenderImageExport, TheGpusMeshOfCurvedLeavesMergesAsTheReferences) {
    TempDir dir;
    const std::string scene = std::string(STRATA_TEST_DIR) + "/../examples/openscad_logo.csg";
    const Solid gpu = read(exportMesh(dir, scene, "gpu.off"));
    const Solid cpu = read(exportMesh(dir, scene, "cpu.off", {"--reference"}));
    expectSound(gpu, "gpu");
    expectSound(cpu, "reference");
    EXPECT_NEAR(PMP::volume(gpu), PMP::volume(cpu), 1e-5 * PMP::volume(cpu));
    EXPECT_LT(double(gpu.number_of_faces()), 1.1 * double(cpu.number_of_faces()));
}

TEST(StrataRenderImageExport, EveryFormatHoldsAClosedSolid) {
    TempDir dir;
    const std::string scene = dir.write("cut.csg", kCubeMinusSphere);
    for (const std::string ext : {".stl", ".obj", ".off"}) {
        const Solid s = read(exportMesh(dir, scene, "cut" + ext, {"--export-resolution", "24"}));
        EXPECT_TRUE(CGAL::is_closed(s)) << ext;
        EXPECT_TRUE(PMP::is_outward_oriented(s)) << ext;
    }
}

std::vector<float> readDepth(const std::string& path, int& w, int& h) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    w = spec.width;
    h = spec.height;
    std::vector<float> pixels(static_cast<std::size_t>(w) * h * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
    std::vector<float> depth(static_cast<std::size_t>(w) * h);
    for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = pixels[i * spec.nchannels];
    return depth;
}

TEST(StrataRenderImageExport, RendersAsTheSceneDoesToWithinACell) {
    TempDir dir;
    const std::string scene = dir.write("cut.csg", kCubeMinusSphere);
    const int resolution = 64;
    const std::string mesh = exportMesh(dir, scene, "cut.off", {"--export-resolution", std::to_string(resolution)});
    const std::vector<std::string> view{"--imgsize", "200,160", "--camera", "40,-55,35,0,0,0"};
    std::vector<std::string> a{kExe, scene, "--depth", dir / "scene.exr"}, b{kExe, mesh, "--depth", dir / "mesh.exr"};
    a.insert(a.end(), view.begin(), view.end());
    b.insert(b.end(), view.begin(), view.end());
    ASSERT_EQ(runProcess(a).exitCode, 0);
    ASSERT_EQ(runProcess(b).exitCode, 0);
    int w = 0, h = 0;
    const std::vector<float> sceneDepth = readDepth(dir / "scene.exr", w, h);
    const std::vector<float> meshDepth = readDepth(dir / "mesh.exr", w, h);
    ASSERT_EQ(sceneDepth.size(), meshDepth.size());
    // A cell is 20 / resolution; along a grazing view ray a cell's error
    // can stretch, so the bound is two cells, and silhouettes may move by
    // a pixel (left out as pixels whose neighbours disagree in coverage).
    const double cell = 20.0 / resolution;
    std::size_t compared = 0, off = 0;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            bool edge = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const std::size_t j = static_cast<std::size_t>(y + dy) * w + (x + dx);
                    edge = edge || std::isfinite(sceneDepth[j]) != std::isfinite(sceneDepth[i]) ||
                           std::isfinite(meshDepth[j]) != std::isfinite(meshDepth[i]);
                }
            if (edge) continue;
            ++compared;
            const bool a1 = std::isfinite(sceneDepth[i]), b1 = std::isfinite(meshDepth[i]);
            if (a1 != b1 || (a1 && std::fabs(sceneDepth[i] - meshDepth[i]) > 2.0 * cell)) ++off;
        }
    }
    EXPECT_GT(compared, 20000u);
    EXPECT_LE(off, compared / 1000) << off << " of " << compared << " pixels differ by more than two cells";
}

// A wall or a gap thinner than a cell that no grid point sees would vanish
// from the contour while the mesh stays closed: refused in one line that
// names it and the resolution that sees it, which then exports it, by the
// GPU and by the reference alike.
TEST(StrataRenderImageExport, WallsAndGapsThinnerThanACellAreRefusedNeverDropped) {
    TempDir dir;
    const std::string plate = "difference() { cube(size = [10, 10, 0.2]); "
                              "multmatrix([[1,0,0,5],[0,1,0,5],[0,0,1,-1],[0,0,0,1]]) cylinder(h = 2, r = 2, $fn = 16); }";
    struct Case {
        std::string name, text, what;
    };
    const std::vector<Case> cases{
        {"plate", plate + "\n", "a wall 0.2 thick"},
        // Turned 20 degrees about x: 0.2 / cos 20 = 0.213 along z.
        {"tilted", "multmatrix([[1,0,0,0],[0,0.939693,-0.34202,0],[0,0.34202,0.939693,0],[0,0,0,1]]) " + plate + "\n",
         "a wall 0.213 thick"},
        {"gap", "cube(size = [5, 5, 5]); multmatrix([[1,0,0,5.2],[0,1,0,0],[0,0,1,0],[0,0,0,1]]) cube(size = [5, 5, 5]);\n",
         "a gap 0.2 wide"},
    };
    for (const Case& c : cases) {
        for (const bool reference : {false, true}) {
            SCOPED_TRACE(c.name + (reference ? " (reference)" : " (GPU)"));
            const std::string scene = dir.write(c.name + ".csg", c.text);
            std::vector<std::string> argv{kExe, scene, "--export", dir / "thin.stl", "--export-sampled", "--export-resolution", "16"};
            if (reference) argv.push_back("--reference");
            const ProcessResult r = runProcess(argv);
            EXPECT_NE(r.exitCode, 0);
            EXPECT_EQ(lineCount(r.err), 1) << r.err;
            EXPECT_EQ(r.err.rfind(scene + ": export: " + c.what + " near (", 0), 0u) << r.err;
            EXPECT_FALSE(std::filesystem::exists(dir / "thin.stl"));
            std::smatch at;
            ASSERT_TRUE(std::regex_search(r.err, at, std::regex(R"(give --export-resolution (\d+) or more)"))) << r.err;
            std::vector<std::string> again{"--export-resolution", at[1].str()};
            if (reference) again.push_back("--reference");
            // In one piece, closed and facing out, with the volume of the
            // exact result. (Not checked here: that the contour is free of
            // self-intersections, which the sampled export does not yet
            // promise on a turned thin plate.)
            const Solid s = read(exportMesh(dir, scene, c.name + (reference ? "-ref.off" : "-gpu.off"), again));
            EXPECT_TRUE(CGAL::is_closed(s));
            EXPECT_TRUE(PMP::is_outward_oriented(s));
            std::vector<std::size_t> piece(s.number_of_faces());
            EXPECT_EQ(PMP::connected_components(s, CGAL::make_property_map(piece)), c.name == "gap" ? 2u : 1u);
            const double exact = PMP::volume(read(exportMesh(dir, scene, c.name + "-exact.off", {"--export-exact"})));
            EXPECT_NEAR(PMP::volume(s), exact, 0.05 * exact) << c.name;
        }
    }
}

TEST(StrataRenderImageExport, BadResolutionsAreOneLineAndWriteNothing) {
    TempDir dir;
    const std::string cube = dir.write("cube.csg", "cube(size = 1);\n");
    const std::string flat = dir.write("flat.csg", "square(size = 1);\n");
    const std::string empty = dir.write("empty.csg", "difference() { cube(size = 1); cube(size = 1); }\n");
    struct Case {
        std::vector<std::string> args;
        std::string prefix;
    };
    const std::vector<Case> cases{
        {{cube, "--export", dir / "a.stl", "--export-sampled", "--export-resolution", "4"},
         "strata-render: --export-resolution: expected a whole number from 8 to 4096"},
        {{cube, "--export", dir / "a.stl", "--export-sampled", "--export-resolution", "many"},
         "strata-render: --export-resolution: expected a whole number from 8 to 4096"},
        {{cube, "--export-sampled", "--export-resolution", "64"}, "strata-render: --export-sampled: give --export FILE too"},
        {{cube, "--export", dir / "a.stl", "--export-resolution", "64"},
         "strata-render: --export-resolution: the exact export has no resolution; give --export-sampled too"},
        {{cube, "--export", dir / "a.stl", "--export-exact", "--export-sampled"},
         "strata-render: --export-exact and --export-sampled: give one of them"},
        {{flat, "--export", dir / "a.stl"}, flat + ": a 2D model has no solid to export"},
        {{empty, "--export", dir / "a.stl"}, empty + ": the CSG result is empty: nothing to export"},
        {{cube, "--export", dir / "nowhere/a.stl"}, (dir / "nowhere/a.stl") + ": cannot write"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> argv{kExe};
        argv.insert(argv.end(), c.args.begin(), c.args.end());
        const ProcessResult r = runProcess(argv);
        EXPECT_NE(r.exitCode, 0) << c.prefix;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind(c.prefix, 0), 0u) << r.err;
        EXPECT_EQ(dir.files(), (std::vector<std::string>{"cube.csg", "empty.csg", "flat.csg"})) << c.prefix;
    }
}

}  // namespace
