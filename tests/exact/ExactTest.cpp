// The exact evaluation of a subtree (strata/geometry/Exact.h) against closed
// forms: the volume of a result is the volumes of its leaves' meshes
// combined as the sets are, where the leaves lie apart or one inside
// another, and the result is one closed, oriented mesh.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "../mesh/MeshTestUtil.h"
#include "strata/exact/Exact.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using mesh::Mesh;

namespace {

scene::Tree parse(const std::string& text) {
    std::istringstream in(text);
    return scene::parseCsg(in, "exact.csg", ".");
}

std::string ballAt(double x, double y, double z, double r) {
    return "multmatrix([[1, 0, 0, " + std::to_string(x) + "], [0, 1, 0, " + std::to_string(y) + "], [0, 0, 1, " +
           std::to_string(z) + "], [0, 0, 0, 1]]) sphere($fn = 16, r = " + std::to_string(r) + ");\n";
}

// The root's exact result, and the volumes of the tree's leaf meshes.
struct Evaluated {
    Mesh result;
    std::vector<double> leafVolumes;
};

Evaluated evaluate(const scene::Tree& tree) {
    const model::Model model = model::buildModel(tree);
    Evaluated e{exact::exactResult(tree, tree.root, model.leafMeshes, model::objectMesh), {}};
    for (const Mesh& m : model.leafMeshes) e.leafVolumes.push_back(mesh::test::signedVolume(m));
    return e;
}

}  // namespace

TEST(ExactResult, ACubeLessBallsInsideItLosesEachBallsVolume) {
    // Eight balls apart inside a cube.
    std::string text = "difference() {\ncube(size = [10, 10, 10], center = false);\n";
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) text += ballAt(2.5 + 5 * i, 2.5 + 5 * j, 2.5 + 5 * k, 1.5);
    const Evaluated e = evaluate(parse(text + "}\n"));
    double expected = e.leafVolumes[0];
    for (std::size_t i = 1; i < e.leafVolumes.size(); ++i) expected -= e.leafVolumes[i];
    EXPECT_NEAR(mesh::test::signedVolume(e.result), expected, 1e-9 * e.leafVolumes[0]);
    EXPECT_TRUE(mesh::checkMesh(e.result).ok()) << mesh::checkMesh(e.result).describe();
}

TEST(ExactResult, AResultTouchingItselfAtPointsIsExactAndGoesOnToTheNextBoolean) {
    // The tetrahedron x, y, z >= 0, x + y + z <= 3 less the box |x|, |y| <= 1,
    // |z| <= 2, which holds its apex: what is left is three parts, two of
    // which meet the third at the single points (1, 0, 2) and (0, 1, 2).
    // The box takes away 1 (below x + y = 1, two high) + 5/6 (above it,
    // under the slanted face), so 9/2 - 11/6 = 8/3 is left. Found by the
    // geometry fuzzer: the exact export crashed on it.
    const std::string tetra = "polyhedron(points = [[0, 0, 0], [3, 0, 0], [0, 3, 0], [0, 0, 3]], "
                              "faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]], convexity = 1);\n";
    const std::string box = "cube(size = [2, 2, 4], center = true);\n";
    const Evaluated e = evaluate(parse("difference() {\n" + tetra + box + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(e.result), 8.0 / 3.0, 1e-12);
    EXPECT_TRUE(mesh::checkMesh(e.result).ok()) << mesh::checkMesh(e.result).describe();
    // ... and such a result takes part in a further boolean: less the box
    // [2, 3] x [-1, 1] x [-1, 1], which cuts the tip (3 - x)^2 / 2 over
    // x in [2, 3], 1/6, off the part beyond x = 1.
    const std::string tip = "multmatrix([[1, 0, 0, 2], [0, 1, 0, -1], [0, 0, 1, -1], [0, 0, 0, 1]]) {\n"
                            "cube(size = [1, 2, 2], center = false);\n}\n";
    const Evaluated next = evaluate(parse("difference() {\n" + tetra + box + tip + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(next.result), 5.0 / 2.0, 1e-12);
    EXPECT_TRUE(mesh::checkMesh(next.result).ok()) << mesh::checkMesh(next.result).describe();
}

TEST(ExactResult, AClosedMeshThatEnclosesNothingIsEmpty) {
    // Two of the points coincide: the faces lie back to back and enclose no
    // volume. Booleans are regularized, so it is the empty solid wherever it
    // stands (CGAL's Nef overlay asserted on it; found by the geometry fuzzer).
    const std::string flat = "polyhedron(points = [[0, 0, 0], [6, 0, 0], [0, 0, 0], [0, 0, 8]], "
                             "faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]], convexity = 1);\n";
    const std::string box = "cube(size = [2, 2, 2], center = false);\n";
    EXPECT_TRUE(evaluate(parse("difference() {\n" + flat + box + "}\n")).result.triangles.empty());
    EXPECT_TRUE(evaluate(parse("intersection() {\n" + box + flat + "}\n")).result.triangles.empty());
    const Evaluated united = evaluate(parse("union() {\n" + box + flat + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(united.result), 8.0, 1e-12);
    const Evaluated less = evaluate(parse("difference() {\n" + box + flat + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(less.result), 8.0, 1e-12);
    // Among other operands, gathered with them into groups that take part
    // in one boolean each, it still adds and takes away nothing.
    const std::string ball = ballAt(1, 1, 1, 0.5), away = ballAt(5, 5, 5, 0.5);
    const Evaluated among = evaluate(parse("difference() {\n" + box + flat + ball + away + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(among.result), 8.0 - among.leafVolumes[2], 1e-12);
    const Evaluated added = evaluate(parse("union() {\n" + box + flat + away + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(added.result), 8.0 + added.leafVolumes[2], 1e-12);
    EXPECT_TRUE(mesh::checkMesh(among.result).ok()) << mesh::checkMesh(among.result).describe();
}

TEST(ExactResult, SolidsApartUniteWithTheirVolumesSummed) {
    // Joined with no boolean: their boxes do not meet.
    std::string text = "union() {\n";
    for (int i = 0; i < 5; ++i) text += ballAt(4.0 * i, 0, 0, 1.0 + 0.2 * i);
    const Evaluated e = evaluate(parse(text + "}\n"));
    double expected = 0;
    for (double v : e.leafVolumes) expected += v;
    EXPECT_NEAR(mesh::test::signedVolume(e.result), expected, 1e-9 * expected);
    EXPECT_TRUE(mesh::checkMesh(e.result).ok()) << mesh::checkMesh(e.result).describe();
}

TEST(ExactResult, SolidsApartHaveNoIntersectionAndTakeNothingAway) {
    const Evaluated apart = evaluate(parse("intersection() {\n" + ballAt(0, 0, 0, 1) + ballAt(5, 0, 0, 1) + "}\n"));
    EXPECT_TRUE(apart.result.triangles.empty());
    const Evaluated outside = evaluate(parse("difference() {\n" + ballAt(0, 0, 0, 1) + ballAt(5, 0, 0, 1) +
                                             ballAt(0, 5, 0, 1) + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(outside.result), outside.leafVolumes[0], 1e-9);
}

TEST(ExactResult, ManyOperandsInBoxesApartAndMeetingGiveTheClosedForm) {
    // A 12 x 12 x 3 block less a 5 x 5 grid of balls on its top face, every
    // ball's box touching its neighbours' (so they cannot all be taken out
    // in one group), plus a 5 x 5 grid of cubes standing on the block: each
    // ball takes away its lower half, each cube adds its own volume.
    std::string balls, cubes;
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
            balls += ballAt(2 + 2 * i, 2 + 2 * j, 3, 1);
            cubes += "multmatrix([[1, 0, 0, " + std::to_string(1.6 + 2 * i) + "], [0, 1, 0, " + std::to_string(1.6 + 2 * j) +
                     "], [0, 0, 1, 3], [0, 0, 0, 1]]) cube(size = [0.8, 0.8, 0.5], center = false);\n";
        }
    }
    const std::string block = "cube(size = [12, 12, 3], center = false);\n";
    const Evaluated cut = evaluate(parse("difference() {\n" + block + balls + "}\n"));
    double halves = 0;
    for (std::size_t i = 1; i < cut.leafVolumes.size(); ++i) halves += cut.leafVolumes[i] / 2;
    EXPECT_NEAR(mesh::test::signedVolume(cut.result), 432.0 - halves, 1e-9);
    EXPECT_TRUE(mesh::checkMesh(cut.result).ok()) << mesh::checkMesh(cut.result).describe();
    const Evaluated built = evaluate(parse("union() {\n" + block + cubes + "}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(built.result), 432.0 + 25 * 0.32, 1e-9);
    EXPECT_TRUE(mesh::checkMesh(built.result).ok()) << mesh::checkMesh(built.result).describe();
}

TEST(ExactResult, OverlappingSubtrahendsAreTakenAwayOnce) {
    // Two balls that overlap each other and the cube's corner: the cube
    // loses their union, whose volume the overlapping pair's own exact union gives.
    const std::string balls = ballAt(0, 0, 0, 2) + ballAt(1, 0, 0, 2);
    const Evaluated cut = evaluate(parse("difference() {\ncube(size = [4, 4, 4], center = false);\n" + balls + "}\n"));
    const Evaluated both = evaluate(parse("intersection() {\ncube(size = [4, 4, 4], center = false);\nunion() {\n" +
                                          balls + "}\n}\n"));
    EXPECT_NEAR(mesh::test::signedVolume(cut.result) + mesh::test::signedVolume(both.result), 64.0, 1e-9);
    EXPECT_TRUE(mesh::checkMesh(cut.result).ok()) << mesh::checkMesh(cut.result).describe();
}

namespace {

// A step: [0, 1] x [0, 1] x [0, 1] beside [1, 2] x [0, 1] x [0, 2]. Its
// union is a prism over an L of six corners: two caps of four triangles,
// six sides of two, twelve points; the corners the two boxes shared on the
// straight bottom edges are on no face's outline.
const std::string kStep = "union() {\ncube(size = [1, 1, 1], center = false);\n"
                          "multmatrix([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                          "cube(size = [1, 1, 2], center = false);\n}\n";

std::size_t pointsUsed(const Mesh& m) {
    std::vector<bool> used(m.positions.size(), false);
    for (const auto& t : m.triangles)
        for (uint32_t v : t) used[v] = true;
    return static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
}

}  // namespace

TEST(ExactResult, FlatFacesComeOutWithTheTrianglesTheirOutlinesNeed) {
    const Evaluated step = evaluate(parse(kStep));
    EXPECT_NEAR(mesh::test::signedVolume(step.result), 3.0, 1e-12);
    EXPECT_EQ(step.result.triangles.size(), 20u);
    EXPECT_EQ(pointsUsed(step.result), 12u);
    EXPECT_TRUE(mesh::checkMesh(step.result).ok()) << mesh::checkMesh(step.result).describe();

    // A 10 x 10 x 2 plate less a 16-sided prism through it: the top and the
    // bottom are squares with a hole, 16 + 4 triangles each (a polygon of V
    // corners and h holes takes V + 2h - 2); four sides and the hole's 16
    // walls take two each: 80 triangles on 40 points.
    const int n = 16;
    const Evaluated plate = evaluate(parse("difference() {\ncube(size = [10, 10, 2], center = false);\n"
                                           "multmatrix([[1, 0, 0, 5], [0, 1, 0, 5], [0, 0, 1, -1], [0, 0, 0, 1]]) "
                                           "cylinder($fn = 16, h = 4, r1 = 2, r2 = 2, center = false);\n}\n"));
    const double hole = 0.5 * n * 4.0 * std::sin(2.0 * 3.14159265358979323846 / n);
    EXPECT_NEAR(mesh::test::signedVolume(plate.result), 2.0 * (100.0 - hole), 1e-9);
    EXPECT_EQ(plate.result.triangles.size(), static_cast<std::size_t>(4 * n + 16));
    EXPECT_EQ(pointsUsed(plate.result), static_cast<std::size_t>(2 * n + 8));
    EXPECT_TRUE(mesh::checkMesh(plate.result).ok()) << mesh::checkMesh(plate.result).describe();
}

TEST(ExactResult, ASubassemblyTurnedOrMirroredIsTheSameSolidMoved) {
    // The step under a turn about an oblique axis, then under a mirror and a
    // shift: the booleans are done before the steps and the result moved out
    // through them; faces flush before stay flush, and a mirror keeps the
    // surface facing out.
    const std::string turn = "multmatrix([[0.816497, 0.408248, 0.408248, 0], [0, 0.707107, -0.707107, 0], "
                             "[-0.57735, 0.57735, 0.57735, 0], [0, 0, 0, 1]])";
    const std::string mirror = "multmatrix([[-1, 0, 0, 3], [0, 1, 0, 0.1], [0, 0, 1, 0], [0, 0, 0, 1]])";
    // The turn's rows are unit length to 1e-6: the volume scales by its determinant.
    const glm::dmat3 m(0.816497, 0, -0.57735, 0.408248, 0.707107, 0.57735, 0.408248, -0.707107, 0.57735);
    const double scale = glm::determinant(m);
    for (const std::string& text : {turn + " {\n" + kStep + "}\n", mirror + " {\n" + turn + " {\n" + kStep + "}\n}\n",
                                    turn + " {\ndifference() {\n" + mirror + " {\n" + kStep + "}\n" + mirror +
                                        " cube(size = [1, 1, 1], center = false);\n}\n}\n"}) {
        SCOPED_TRACE(text);
        const Evaluated e = evaluate(parse(text));
        const bool cut = text.find("difference") != std::string::npos;
        EXPECT_NEAR(mesh::test::signedVolume(e.result), (cut ? 2.0 : 3.0) * scale, 1e-9);
        EXPECT_TRUE(mesh::checkMesh(e.result).ok()) << mesh::checkMesh(e.result).describe();
        if (!cut) {
            // Where the leaves' own meshes are, moved one by one.
            mesh::Bounds leaves, result = mesh::boundsOf(e.result);
            for (const Mesh& leaf : model::buildModel(parse(text)).leafMeshes) leaves.extend(mesh::boundsOf(leaf));
            for (int k = 0; k < 3; ++k) {
                EXPECT_NEAR(result.min[k], leaves.min[k], 1e-12);
                EXPECT_NEAR(result.max[k], leaves.max[k], 1e-12);
            }
            EXPECT_EQ(e.result.triangles.size(), 20u);
            EXPECT_EQ(pointsUsed(e.result), 12u);
        }
    }
    // A step that flattens space is no frame to move a result out of: the
    // flattened step encloses nothing.
    const Evaluated flat = evaluate(parse("multmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]) {\n" +
                                          turn + " {\n" + kStep + "}\n}\n"));
    EXPECT_TRUE(flat.result.triangles.empty());
}

namespace {

std::string barAt(char axis, double u, double v, double width) {
    // A bar 33 long through a block of 27, across `axis`, centred at (u, v)
    // in the other two coordinates (in x, y, z order).
    const auto k = static_cast<std::size_t>(axis - 'x');
    std::array<double, 3> corner{}, size{};
    corner[k] = -3.0;
    size[k] = 33.0;
    const std::array<double, 2> centre{u, v};
    for (std::size_t i = 0, other = 0; i < 3; ++i) {
        if (i == k) continue;
        corner[i] = centre[other++] - width / 2;
        size[i] = width;
    }
    std::ostringstream out;
    out << "multmatrix([[1, 0, 0, " << corner[0] << "], [0, 1, 0, " << corner[1] << "], [0, 0, 1, " << corner[2]
        << "], [0, 0, 0, 1]]) cube(size = [" << size[0] << ", " << size[1] << ", " << size[2] << "], center = false);\n";
    return out.str();
}

// A level-two Menger sponge of side 27: the block less, across each axis, the
// carpet's holes: one bar 9 wide through the middle and eight 3 wide through
// the middles of the cells around it. `grouped`: the bars in nested groups
// (the block less one union of three unions, as OpenSCAD's recursive modules
// write it); otherwise each bar a child of the difference.
std::string sponge(bool grouped) {
    std::string text = "difference() {\ncube(size = [27, 27, 27], center = false);\n";
    if (grouped) text += "group() {\n";
    for (char axis : {'x', 'y', 'z'}) {
        if (grouped) text += "group() {\n";
        text += barAt(axis, 13.5, 13.5, 9.0);
        if (grouped) text += "group() {\n";
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (i != 1 || j != 1) text += barAt(axis, 4.5 + 9 * i, 4.5 + 9 * j, 3.0);
        if (grouped) text += "}\n}\n";
    }
    if (grouped) text += "}\n";
    return text + "}\n";
}

}  // namespace

TEST(ExactResult, ASpongeCutByGroupsOfBarsIsTheClosedFormAndTheSameMeshAsByLoneBars) {
    // 27^3 (20/27)^2: each level keeps 20 of every 27 cells.
    const Evaluated grouped = evaluate(parse(sponge(true)));
    EXPECT_NEAR(mesh::test::signedVolume(grouped.result), 10800.0, 1e-9);
    EXPECT_TRUE(mesh::checkMesh(grouped.result).ok()) << mesh::checkMesh(grouped.result).describe();
    // A difference takes a union's operands in its place: the grouped bars
    // must give the very mesh the bars as the difference's own children give.
    const Evaluated lone = evaluate(parse(sponge(false)));
    EXPECT_EQ(grouped.result.positions, lone.result.positions);
    EXPECT_EQ(grouped.result.triangles, lone.result.triangles);
}
