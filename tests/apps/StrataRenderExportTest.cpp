// strata-render --export --export-exact, run as a user runs it, on models
// whose faces coincide (tests/data/coincident: OpenSCAD 2021.01's CSG export
// and its exact CGAL result). The exported mesh is read by CGAL's own reader
// and checked by CGAL, not by strata: closed, outward, free of
// self-intersections, OpenSCAD's volume, and every corner of OpenSCAD's
// result present.

#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <array>
#include <fstream>
#include <iterator>

#include "../io/ThreeMfFile.h"
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
const std::string kData = std::string(STRATA_TEST_DIR) + "/data/coincident/";

Solid read(const std::string& path) {
    Solid s;
    EXPECT_TRUE(CGAL::IO::read_polygon_mesh(path, s)) << path;
    PMP::triangulate_faces(s);
    return s;
}

// How far the corner of `a` farthest from the surface of `b` is from it.
double farthestCorner(const Solid& a, const Solid& b) {
    std::vector<Kernel::Triangle_3> triangles;
    for (const auto f : b.faces()) {
        std::vector<Kernel::Point_3> p;
        for (const auto v : CGAL::vertices_around_face(b.halfedge(f), b)) p.push_back(b.point(v));
        triangles.emplace_back(p[0], p[1], p[2]);
    }
    double farthest = 0;
    for (const auto v : a.vertices()) {
        double nearest = 1e300;
        for (const Kernel::Triangle_3& t : triangles) nearest = std::min(nearest, CGAL::squared_distance(a.point(v), t));
        farthest = std::max(farthest, std::sqrt(nearest));
    }
    return farthest;
}

// What a slicer would find wrong with the file, as the export benchmark's
// audit finds it: nothing (no triangle without area, no open or
// non-manifold edge once equal points are welded, no self-intersection).
void expectClean(const std::string& path) {
    const ProcessResult audit = runProcess({STRATA_MESH_AUDIT_EXE, path});
    EXPECT_EQ(audit.exitCode, 0) << audit.out << audit.err;
    EXPECT_NE(audit.out.find("\"clean\": true"), std::string::npos) << audit.out;
}

// The models whose exact result is a solid (identical_difference's is empty).
std::vector<std::string> models() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(kData))
        if (entry.path().extension() == ".off") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

class ExactExport : public ::testing::TestWithParam<std::string> {};

TEST_P(ExactExport, IsOpenScadsSolidAndPassesCgalsChecks) {
    const std::string name = GetParam();
    TempDir dir;
    const std::string out = dir / (name + ".off");
    const ProcessResult r = runProcess({kExe, kData + name + ".csg", "--export", out, "--export-exact"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(dir.files(), std::vector<std::string>{name + ".off"});  // nothing rendered, nothing else written

    const Solid ours = read(out);
    const Solid theirs = read(kData + name + ".off");
    ASSERT_FALSE(ours.is_empty());
    EXPECT_TRUE(CGAL::is_closed(ours));
    EXPECT_TRUE(PMP::is_outward_oriented(ours));
    EXPECT_FALSE(PMP::does_self_intersect(ours));
    expectClean(out);
    // OpenSCAD prints six significant digits, of the .csg's numbers too.
    const double volume = PMP::volume(theirs);
    EXPECT_NEAR(PMP::volume(ours), volume, 2e-5 * std::fabs(volume)) << name;
    double scale = 0;
    for (const auto v : theirs.vertices()) {
        const Kernel::Point_3& p = theirs.point(v);
        scale = std::max({scale, std::fabs(p.x()), std::fabs(p.y()), std::fabs(p.z())});
    }
    // The same surface: every corner of each lies on the other. (Either may
    // keep corners the other has not: OpenSCAD keeps the imprint of a solid
    // that only touches a face; strata joins coplanar faces.)
    EXPECT_LT(farthestCorner(theirs, ours), 2e-5 * scale) << name << ": a corner of OpenSCAD's is off our surface";
    EXPECT_LT(farthestCorner(ours, theirs), 2e-5 * scale) << name << ": a corner of ours is off OpenSCAD's surface";
}

INSTANTIATE_TEST_SUITE_P(Coincident, ExactExport, ::testing::ValuesIn(models()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// A model of one object has no boolean to evaluate: its own checked mesh is
// the result, as OpenSCAD 2021.01 writes a lone object's polygons (its
// `openscad -o` of this polyhedron: 9 vertices, 14 triangles, the top's
// centre kept). Through a Nef polyhedron the centre was dropped and the top
// retriangulated (8 and 12).
TEST(StrataRenderExport, ALoneObjectIsWrittenAsItsOwnMesh) {
    TempDir dir;
    const std::string scene = dir.write(
        "lone.csg",
        "multmatrix([[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]) {\n"
        "polyhedron(points = [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0], [0, 0, 10], [10, 0, 10], [10, 10, 10], "
        "[0, 10, 10], [5, 5, 10]], faces = [[0, 1, 2], [0, 2, 3], [0, 4, 5], [0, 5, 1], [1, 5, 6], [1, 6, 2], [2, 6, 7], "
        "[2, 7, 3], [3, 7, 4], [3, 4, 0], [4, 8, 5], [5, 8, 6], [6, 8, 7], [7, 8, 4]], convexity = 1);\n}\n");
    const std::string out = dir / "lone.off";
    const ProcessResult r = runProcess({kExe, scene, "--export", out});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Solid ours = read(out);
    EXPECT_EQ(ours.number_of_vertices(), 9u);
    EXPECT_EQ(ours.number_of_faces(), 14u);
    EXPECT_TRUE(CGAL::is_closed(ours));
    EXPECT_TRUE(PMP::is_outward_oriented(ours));
    EXPECT_NEAR(PMP::volume(ours), 1000.0, 1e-9);
    bool centre = false;
    for (const auto v : ours.vertices()) centre = centre || ours.point(v) == Kernel::Point_3(6, 7, 13);
    EXPECT_TRUE(centre) << "the top's centre, moved by the translation";
    expectClean(out);
}

// A plate of separate parts: a union whose children's boxes are apart is
// each child's exact result side by side, without a union of them all. Four
// cubes of 20 each holed through by a 48-sided cylinder of radius 5.
TEST(StrataRenderExport, APlateOfSeparatePartsIsEachPartSideBySide) {
    TempDir dir;
    std::string text = "union() {\n";
    for (int i = 0; i < 4; ++i) {
        text += "multmatrix([[1, 0, 0, " + std::to_string(30 * i) + "], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
                "difference() {\ncube(size = [20, 20, 20], center = false);\n"
                "multmatrix([[1, 0, 0, 10], [0, 1, 0, 10], [0, 0, 1, -1], [0, 0, 0, 1]]) {\n"
                "cylinder($fn = 48, $fa = 12, $fs = 2, h = 22, r1 = 5, r2 = 5, center = false);\n}\n}\n}\n";
    }
    const std::string scene = dir.write("plate.csg", text + "}\n");
    const std::string out = dir / "plate.off";
    const ProcessResult r = runProcess({kExe, scene, "--export", out});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Solid ours = read(out);
    EXPECT_TRUE(CGAL::is_closed(ours));
    EXPECT_TRUE(PMP::is_outward_oriented(ours));
    EXPECT_FALSE(PMP::does_self_intersect(ours));
    Solid parts = ours;
    const auto component = parts.add_property_map<Solid::Face_index, std::size_t>("f:component").first;
    EXPECT_EQ(PMP::connected_components(parts, component), 4u);
    const double hole = 0.5 * 48 * 25 * std::sin(2 * M_PI / 48);  // the 48-gon's area
    EXPECT_NEAR(PMP::volume(ours), 4 * (8000 - 20 * hole), 1e-3);
    expectClean(out);
}

TEST(StrataRenderExport, EveryFormatHoldsTheSameSolid) {
    TempDir dir;
    const std::string scene = kData + "plate_cylinder_hole_fn40.csg";
    double volume = 0;
    for (const char* ext : {".off", ".stl", ".obj"}) {
        const std::string out = dir / (std::string("plate") + ext);
        const ProcessResult r = runProcess({kExe, scene, "--export", out, "--export-exact"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Solid s = read(out);
        EXPECT_TRUE(CGAL::is_closed(s)) << ext;
        if (volume == 0) volume = PMP::volume(s);
        EXPECT_NEAR(PMP::volume(s), volume, 1e-5 * volume) << ext;  // STL holds single precision
    }
    // 3MF is a zip archive that CGAL does not read here; MeshWriterTest reads it through lib3mf.
    const ProcessResult r = runProcess({kExe, scene, "--export", dir / "plate.3mf", "--export-exact"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_GT(std::filesystem::file_size(dir / "plate.3mf"), 100u);
}

// A 3MF export colours each triangle by the leaf whose surface it lies on,
// read back through lib3mf: a red cube, a blue sphere, and a grey-less cut.
TEST(StrataRenderExport, ThreeMfColoursEachTriangleByItsLeaf) {
    TempDir dir;
    const std::string scene = dir.write("colours.csg",
                                        "color([1, 0, 0, 1]) difference() { cube(size = 10); "
                                        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 5], [0, 0, 1, 5], [0, 0, 0, 1]]) cube(size = 10); }\n"
                                        "multmatrix([[1, 0, 0, 30], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                                        "color([0, 0, 1, 1]) sphere($fn = 16, r = 5);\n");
    // The exact export's triangles lie on the leaves' faces; the sampled
    // one's within a cell of them (the nearest face gives the colour).
    for (const std::string sampling : {"", "--export-resolution=48"}) {
        SCOPED_TRACE(sampling);
        std::vector<std::string> argv{kExe, scene, "--export", dir / "c.3mf"};
        if (!sampling.empty()) argv.insert(argv.end(), {"--export-sampled", sampling});
        const ProcessResult r = runProcess(argv);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        std::ifstream in(dir / "c.3mf", std::ios::binary);
        std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const strata::testing::ThreeMfFile file(bytes);
        NMR::PLib3MFModelResource* mesh = file.mesh();
        NMR::PLib3MFModelResource* group = file.materials();
        ASSERT_NE(group, nullptr);
        NMR::PLib3MFPropertyHandler* properties = file.properties();
        DWORD triangles = 0;
        ASSERT_EQ(NMR::lib3mf_meshobject_gettrianglecount(mesh, &triangles), LIB3MF_OK);
        ASSERT_GT(triangles, 20u);
        int red = 0, blue = 0;
        for (DWORD t = 0; t < triangles; ++t) {
            NMR::MODELMESHTRIANGLE tri{};
            ASSERT_EQ(NMR::lib3mf_meshobject_gettriangle(mesh, t, &tri), LIB3MF_OK);
            float x = 0;
            for (int k = 0; k < 3; ++k) {
                NMR::MODELMESHVERTEX v{};
                ASSERT_EQ(NMR::lib3mf_meshobject_getvertex(mesh, tri.m_nIndices[k], &v), LIB3MF_OK);
                x += v.m_fPosition[0] / 3.0f;
            }
            DWORD groupId = 0, index = 0;
            ASSERT_EQ(NMR::lib3mf_propertyhandler_getbasematerial(properties, t, &groupId, &index), LIB3MF_OK);
            BYTE rgba[4] = {};
            ASSERT_EQ(NMR::lib3mf_basematerial_getdisplaycolor(group, index, &rgba[0], &rgba[1], &rgba[2], &rgba[3]), LIB3MF_OK);
            // The block (and its cut, by a subtrahend under the same color()) is red, the sphere blue.
            if (x < 15.0f) {
                EXPECT_EQ((std::array<int, 3>{rgba[0], rgba[1], rgba[2]}), (std::array<int, 3>{255, 0, 0})) << t;
                ++red;
            } else {
                EXPECT_EQ((std::array<int, 3>{rgba[0], rgba[1], rgba[2]}), (std::array<int, 3>{0, 0, 255})) << t;
                ++blue;
            }
        }
        EXPECT_GT(red, 0);
        EXPECT_GT(blue, 0);
    }
}

// Voids: a ball cut out of a block's inside leaves a second shell, and a
// ball left inside that void a third. The volumes must be the block's less
// the void's plus the island's, each ball's measured on its own export.
// OpenSCAD's logo, coarser: a sphere minus three crossing cylinders. Exact
// corners of its seams lie closer together than a float's step (and a
// double's), so rounding alone would leave triangles without area and
// triangles crossing; every format comes out clean.
TEST(StrataRenderExport, ExactExportIsCleanAtTheFilesPrecision) {
    TempDir dir;
    const std::string scene = dir.write("logo.csg",
                                        "difference() { sphere($fn = 40, r = 25); "
                                        "cylinder($fn = 40, h = 62.5, r1 = 12.5, r2 = 12.5, center = true); "
                                        "multmatrix([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]]) "
                                        "cylinder($fn = 40, h = 62.5, r1 = 12.5, r2 = 12.5, center = true); "
                                        "multmatrix([[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]]) "
                                        "cylinder($fn = 40, h = 62.5, r1 = 12.5, r2 = 12.5, center = true); }\n");
    for (const std::string ext : {".stl", ".off", ".obj"}) {
        SCOPED_TRACE(ext);
        const ProcessResult r = runProcess({kExe, scene, "--export", dir / ("logo" + ext)});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        expectClean(dir / ("logo" + ext));
    }
}

// The sampled export (CPU sampler) of two of OpenSCAD's examples whose
// contour, rebuilt on the leaves' planes, crossed itself at 64 cells in
// hundreds of places and had edges of four triangles once welded (thin
// plates a cell apart, in example018; small facets close together, in the
// imported mesh): the file a slicer reads is clean, with no warning.
TEST(StrataRenderExport, SampledExportOfTangledModelsIsClean) {
    TempDir dir;
    for (const std::string model : {"tests/bench/models/Old_example018.csg", "examples/imported_mesh.csg"}) {
        SCOPED_TRACE(model);
        const std::string out = dir / "sampled.stl";
        const ProcessResult r = runProcess({kExe, std::string(STRATA_TEST_DIR) + "/../" + model, "--export", out,
                                            "--export-sampled", "--export-resolution", "64", "--reference"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
        expectClean(out);
    }
}

// Every model of the real-model set and the bundled examples, exported
// exactly and sampled (CPU sampler, 512 cells), as a slicer reads the
// files: clean, or refused in one line (a 2D model has no solid; a wall
// thinner than a cell would be lost). Minutes of work, so out of the
// default run: --gtest_also_run_disabled_tests
// --gtest_filter='*EveryRealModel*' runs it.
TEST(StrataRenderExport, DISABLED_EveryRealModelExportsClean) {
    std::vector<std::filesystem::path> models;
    for (const char* folder : {"/bench/models", "/../examples"}) {
        for (const auto& entry : std::filesystem::directory_iterator(std::string(STRATA_TEST_DIR) + folder))
            if (entry.path().extension() == ".csg") models.push_back(entry.path());
    }
    std::sort(models.begin(), models.end());
    ASSERT_GT(models.size(), 50u);
    TempDir dir;
    for (const auto& model : models) {
        SCOPED_TRACE(model.filename().string());
        for (const bool sampled : {false, true}) {
            const std::string out = dir / (sampled ? "sampled.stl" : "exact.stl");
            std::vector<std::string> argv{kExe, model.string(), "--export", out, "-q"};
            if (sampled) argv.insert(argv.end(), {"--export-sampled", "--reference"});
            const ProcessResult r = runProcess(argv);
            if (r.exitCode != 0) {
                EXPECT_TRUE(r.err.find("2D model") != std::string::npos ||
                            (sampled && r.err.find("thinner than a cell") != std::string::npos))
                    << r.err;
                EXPECT_EQ(lineCount(r.err), 1u) << r.err;
                continue;
            }
            expectClean(out);
        }
    }
}

// A cube pierced by three crossing bars, all tilted by one rotation (the
// first step of OpenSCAD's tilted Menger sponge). The bars' side faces are
// flush with each other before the rotation; moved one leaf at a time and
// rounded, they would be a rounding apart after it and leave slivers that
// cross once written. Moved exactly, step by step, the result is the
// closed form's solid and clean.
TEST(StrataRenderExport, ExactExportKeepsFacesFlushUnderARotation) {
    TempDir dir;
    const std::string bar = "cube(size = [110, 33.3333, 33.3333], center = true); ";
    const std::string scene = dir.write(
        "pierced.csg",
        "multmatrix([[0.816497, 0.408248, 0.408248, 0], [0, 0.707107, -0.707107, 0], [-0.57735, 0.57735, 0.57735, 0], "
        "[0, 0, 0, 1]]) difference() { cube(size = [100, 100, 100], center = true); " + bar +
            "multmatrix([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) " + bar +
            "multmatrix([[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]]) " + bar + "}\n");
    for (const std::string ext : {".stl", ".off"}) {
        SCOPED_TRACE(ext);
        const std::string out = dir / ("pierced" + ext);
        const ProcessResult r = runProcess({kExe, scene, "--export", out});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        expectClean(out);
        // The cube less three bars, less the overlaps counted twice; the
        // rotation's rows are unit length to 1e-6.
        const double side = 33.3333;
        const double expected = 1e6 - (3 * 100 * side * side - 2 * side * side * side);
        EXPECT_NEAR(PMP::volume(read(out)), expected, 1e-5 * expected);
    }
}

TEST(StrataRenderExport, ExactExportKeepsVoidsAndIslandsInThem) {
    TempDir dir;
    const std::string at5 = "multmatrix([[1, 0, 0, 5], [0, 1, 0, 5], [0, 0, 1, 5], [0, 0, 0, 1]]) ";
    const std::string hole = at5 + "sphere($fn = 32, r = 3);\n";
    const std::string island = at5 + "sphere($fn = 16, r = 1);\n";
    auto volumeOf = [&](const std::string& name, const std::string& text) {
        const std::string scene = dir.write(name + ".csg", text);
        const ProcessResult r = runProcess({kExe, scene, "--export", dir / (name + ".off"), "--export-exact"});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        const Solid s = read(dir / (name + ".off"));
        EXPECT_TRUE(CGAL::is_closed(s)) << name;
        EXPECT_TRUE(PMP::is_outward_oriented(s)) << name;
        return PMP::volume(s);
    };
    const double ball = volumeOf("hole", hole), small = volumeOf("island", island);
    EXPECT_NEAR(volumeOf("void", "difference() { cube(size = 10); " + hole + "}\n"), 1000.0 - ball, 1e-9 * 1000.0);
    EXPECT_NEAR(volumeOf("both", "difference() { cube(size = 10); " + hole + "}\n" + island),
                1000.0 - ball + small, 1e-9 * 1000.0);
}

// tests/data/flat/hull/minkowski_translated: OpenSCAD 2021.01's CSG export
// of `translate([25, 25, 0]) minkowski() { cube(10); cylinder(r = 2, h = 1); }`
// and `openscad -o` of it: the translation moves the sum once.
TEST(StrataRenderExport, AMinkowskiSumUnderATranslationIsWhereOpenScadPutsIt) {
    TempDir dir;
    const std::string base = std::string(STRATA_TEST_DIR) + "/data/flat/hull/minkowski_translated";
    const ProcessResult r = runProcess({kExe, base + ".csg", "--export", dir / "sum.off", "--export-exact"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Solid ours = read(dir / "sum.off");
    const Solid theirs = read(base + ".off");
    const CGAL::Bbox_3 a = PMP::bbox(ours), b = PMP::bbox(theirs);
    for (int i = 0; i < 3; ++i) {
        // Six significant digits, as OpenSCAD prints.
        EXPECT_NEAR(a.min(i), b.min(i), 1e-4) << i;
        EXPECT_NEAR(a.max(i), b.max(i), 1e-4) << i;
    }
    EXPECT_NEAR(PMP::volume(ours), PMP::volume(theirs), 1e-5 * PMP::volume(theirs));
}

// OpenSCAD 2021.01 on `intersection() { cube(10); minkowski() { } }`:
// "Current top level object is empty."
TEST(StrataRenderExport, AnIntersectionWithAnEmptyMinkowskiSumIsEmpty) {
    TempDir dir;
    const std::string scene = dir.write(
        "empty.csg", "intersection() {\n\tcube(size = [10, 10, 10], center = false);\n\tminkowski(convexity = 0);\n}\n");
    const ProcessResult r = runProcess({kExe, scene, "--export", dir / "a.stl", "--export-exact"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(r.err, scene + ": the CSG result is empty: nothing to export\n");
    EXPECT_EQ(dir.files(), std::vector<std::string>{"empty.csg"});
}

// A 2D model exported as SVG and as DXF, then read back by import() under
// a linear_extrude of height 1: the solid's volume is the drawing's area.
// strata reads it back always, OpenSCAD where it is installed; both give
// the square less the hole, a 24-gon.
TEST(StrataRenderExport, TwoDimensionalModelsExportAsDrawingsThatReadBack) {
    TempDir dir;
    const std::string plate = dir.write(
        "plate.csg",
        "difference() { square(size = [10, 6]); multmatrix([[1, 0, 0, 3], [0, 1, 0, 3], [0, 0, 1, 0], [0, 0, 0, 1]]) "
        "circle($fn = 24, r = 1.5); }\nmultmatrix([[1, 0, 0, 12], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
        "polygon(points = [[0, 0], [4, 0], [0, 3]], paths = undef, convexity = 1);\n");
    const double pi = std::acos(-1.0);
    const double area = 60 - 0.5 * 24 * 1.5 * 1.5 * std::sin(2 * pi / 24) + 6;
    const bool openscad = runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode == 0;
    for (const std::string ext : {".svg", ".dxf"}) {
        SCOPED_TRACE(ext);
        const std::string drawing = dir / ("plate" + ext);
        const ProcessResult r = runProcess({kExe, plate, "--export", drawing});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string back = dir.write("back" + ext + ".csg", "linear_extrude(height = 1, center = false, convexity = 1, "
                                                                  "scale = [1, 1], $fn = 0, $fa = 12, $fs = 2) import(file = \"" +
                                                                  drawing + "\", layer = \"\", origin = [0, 0], scale = 1, "
                                                                  "convexity = 1, $fn = 0, $fa = 12, $fs = 2);\n");
        const std::string ours = dir / ("back" + ext + ".off");
        const ProcessResult readBack = runProcess({kExe, back, "--export", ours});
        ASSERT_EQ(readBack.exitCode, 0) << readBack.err;
        EXPECT_NEAR(PMP::volume(read(ours)), area, 1e-4 * area);
        if (openscad) {
            const std::string theirs = dir / ("openscad" + ext + ".off");
            const ProcessResult o = runProcess({"/usr/bin/env", "openscad", "-o", theirs, back});
            ASSERT_EQ(o.exitCode, 0) << o.err;
            EXPECT_NEAR(PMP::volume(read(theirs)), area, 1e-4 * area);
        }
    }
}

TEST(StrataRenderExport, DeepChainsExportWithoutRecursion) {
    // 50000 differences inside one another (20000 ran out of stack), each
    // of one operand: the exact evaluation walks them with a stack of its own.
    TempDir dir;
    std::string text;
    const int depth = 50000;
    for (int i = 0; i < depth; ++i) text += "difference() {\n";
    text += "cube(size = [1, 2, 3]);\n";
    for (int i = 0; i < depth; ++i) text += "}\n";
    const std::string scene = dir.write("chain.csg", text);
    const ProcessResult r = runProcess({kExe, scene, "--export", dir / "chain.stl"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Solid s = read(dir / "chain.stl");
    EXPECT_NEAR(PMP::volume(s), 6.0, 1e-9);
}

TEST(StrataRenderExport, BadExportsAreOneLineAndWriteNothing) {
    TempDir dir;
    const std::string cube = dir.write("cube.csg", "cube(size = 1);\n");
    const std::string flat = dir.write("flat.csg", "square(size = 1);\n");
    const std::string empty = kData + "identical_difference.csg";
    struct Case {
        std::vector<std::string> args;
        std::string prefix;
    };
    const std::vector<Case> cases{
        {{cube, "--export", dir / "a.ply", "--export-exact"},
         "strata-render: --export: expected a .stl, .off, .obj, .3mf, .svg or .dxf file name"},
        {{cube, "--export", dir / "a.svg"}, cube + ": a 3D model has no 2D drawing to export"},
        {{flat, "--export", dir / "a.dxf", "--export-sampled"}, "strata-render: --export-sampled: a drawing (.svg, .dxf)"},
        {{cube, "--export-exact"}, "strata-render: --export-exact: give --export FILE too"},
        {{cube, "--export", dir / "nowhere/a.stl", "--export-exact"}, (dir / "nowhere/a.stl") + ": cannot write"},
        {{flat, "--export", dir / "a.stl", "--export-exact"}, flat + ": a 2D model has no solid to export"},
        {{empty, "--export", dir / "a.stl", "--export-exact"}, empty + ": the CSG result is empty: nothing to export"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> argv{kExe};
        argv.insert(argv.end(), c.args.begin(), c.args.end());
        const ProcessResult r = runProcess(argv);
        EXPECT_NE(r.exitCode, 0) << c.prefix;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind(c.prefix, 0), 0u) << r.err;
        EXPECT_EQ(dir.files(), (std::vector<std::string>{"cube.csg", "flat.csg"})) << c.prefix;
    }
}

}  // namespace
