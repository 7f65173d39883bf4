#include "strata/model/Model.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "../mesh/MeshTestUtil.h"
#include "strata/core/Error.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using namespace strata::mesh;
using namespace strata::model;
using strata::mesh::test::signedVolume;

namespace {

scene::Leaf leaf(scene::Primitive p, glm::dmat4 t = glm::dmat4(1.0), int line = 1) {
    scene::Leaf l;
    l.primitive = std::move(p);
    l.transform = t;
    l.where = SourceLocation{"scene.csg", line, 5};
    return l;
}

std::string errorOf(const scene::Tree& tree) {
    try {
        buildModel(tree);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(BuildModel, MakesWorldSpaceMeshesPerLeafAndBoundsOverTheCsg) {
    scene::Tree tree;
    const int a = tree.addLeaf(leaf(scene::Cube{{2, 2, 2}, true}));
    const int b = tree.addLeaf(leaf(scene::Sphere{1.0, {8, 12, 2}}, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 5))));
    scene::Leaf bg = leaf(scene::Cube{{1, 1, 1}, false}, glm::translate(glm::dmat4(1.0), glm::dvec3(100, 0, 0)));
    bg.display = scene::Display::Background;
    const int c = tree.addLeaf(bg);
    tree.root = tree.addNode(scene::NodeKind::Difference, {a, b});
    tree.background = {c};

    const Model model = buildModel(tree);
    ASSERT_EQ(model.leafMeshes.size(), 3u);
    for (const Mesh& m : model.leafMeshes) EXPECT_TRUE(checkMesh(m).ok());
    EXPECT_DOUBLE_EQ(signedVolume(model.leafMeshes[0]), 8.0);
    EXPECT_EQ(boundsOf(model.leafMeshes[2]).min, glm::dvec3(100, 0, 0));
    // Sphere $fn = 8: 4 rings at 22.5, 67.5, ... degrees; its top ring is at
    // z = 5 + cos(22.5 degrees), its widest ring has radius sin(67.5 degrees).
    EXPECT_DOUBLE_EQ(model.bounds.min.z, -1.0);
    EXPECT_NEAR(model.bounds.max.z, 5.0 + std::cos(3.14159265358979323846 / 8), 1e-12);
    EXPECT_DOUBLE_EQ(model.bounds.min.x, -1.0);
    EXPECT_DOUBLE_EQ(model.bounds.max.x, 1.0);  // the background cube at x = 100 is left out
}

TEST(BuildModel, EmptyPrimitivesGiveEmptyMeshes) {
    scene::Tree tree;
    const int a = tree.addLeaf(leaf(scene::Cube{{0, 1, 1}, false}));
    const int b = tree.addLeaf(leaf(scene::Cylinder{1.0, 0.0, 0.0, false, {}}));
    tree.root = tree.addNode(scene::NodeKind::Union, {a, b});
    const Model model = buildModel(tree);
    ASSERT_EQ(model.leafMeshes.size(), 2u);
    EXPECT_TRUE(model.leafMeshes[0].triangles.empty());
    EXPECT_TRUE(model.leafMeshes[1].triangles.empty());
    EXPECT_TRUE(model.bounds.empty());
}

TEST(BuildModel, AwkwardButValidPrimitivesPass) {
    scene::Tree tree;
    std::vector<int> kids;
    kids.push_back(tree.addLeaf(leaf(scene::Cylinder{3.0, 2.0, 0.0, false, {}})));   // cone
    kids.push_back(tree.addLeaf(leaf(scene::Cylinder{3.0, 0.0, 2.0, true, {}})));    // inverted cone
    kids.push_back(tree.addLeaf(leaf(scene::Sphere{1e-7, {}})));                     // r < 2^-20
    kids.push_back(tree.addLeaf(leaf(scene::Cylinder{1.0, 1e-7, 1e-7, false, {}})));
    kids.push_back(tree.addLeaf(leaf(scene::Cube{{1, 1, 1}, false}, glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1)))));
    kids.push_back(tree.addLeaf(leaf(scene::Sphere{1e-300, {}})));
    tree.root = tree.addNode(scene::NodeKind::Union, kids);
    const Model model = buildModel(tree);
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        EXPECT_FALSE(model.leafMeshes[i].triangles.empty()) << i;
        EXPECT_TRUE(checkMesh(model.leafMeshes[i]).ok()) << i;
        if (i != 5) {  // 5's volume underflows
            EXPECT_GT(signedVolume(model.leafMeshes[i]), 0.0) << i;
        }
    }
}

TEST(BuildModel, PolyhedronWithRepeatedPointsIsJudgedByTopology) {
    // A tetrahedron whose faces each use their own copies of the corners.
    const glm::dvec3 c[4] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};  // clockwise from outside
    scene::Polyhedron p;
    for (const auto& f : faces) {
        std::vector<int> face;
        for (int i : f) {
            face.push_back(static_cast<int>(p.points.size()));
            p.points.push_back(c[i]);
        }
        p.faces.push_back(face);
    }
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(p));
    const Model model = buildModel(tree);
    EXPECT_EQ(model.leafMeshes[0].positions.size(), 4u);
    EXPECT_DOUBLE_EQ(signedVolume(model.leafMeshes[0]), 8.0 / 6.0);
}

TEST(BuildModel, OpenPolyhedronThrowsWithItsPosition) {
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    p.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}};  // one face missing
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(p, glm::dmat4(1.0), 7));
    EXPECT_EQ(errorOf(tree), "scene.csg:7:5: polyhedron is not a closed solid: not closed: 3 boundary edges");
}

TEST(BuildModel, InsideOutPolyhedronIsTurnedOutwardWithAWarning) {
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    p.faces = {{2, 1, 0}, {1, 3, 0}, {3, 2, 0}, {2, 3, 1}};  // counter-clockwise: wrong for OpenSCAD
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(p, glm::dmat4(1.0), 3));
    const Model model = buildModel(tree);
    EXPECT_NEAR(test::signedVolume(model.leafMeshes[0]), 8.0 / 6.0, 1e-12);  // the tetrahedron, outward
    ASSERT_EQ(model.warnings.size(), 1u);
    EXPECT_EQ(model.warnings[0].message,
              "scene.csg:3:5: warning: polyhedron is inside out (every face wound the wrong way); turned outward");
}

TEST(BuildModel, AnInconsistentlyWoundPolyhedronStaysAnError) {
    // Turning every face is forgiven; faces wound both ways are not a solid, as in OpenSCAD.
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    p.faces = {{2, 1, 0}, {1, 3, 0}, {3, 2, 0}, {2, 1, 3}};  // one face turned the other way
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(p, glm::dmat4(1.0), 3));
    EXPECT_EQ(errorOf(tree), "scene.csg:3:5: polyhedron is not a closed solid: inconsistently oriented: 3 edges");
}

TEST(BuildModel, BadIndexAndMissingImportNameTheLeaf) {
    scene::Polyhedron p;
    p.points = {{0, 0, 0}};
    p.faces = {{0, 1, 2}};
    scene::Tree t1;
    t1.root = t1.addLeaf(leaf(p, glm::dmat4(1.0), 2));
    EXPECT_EQ(errorOf(t1).rfind("scene.csg:2:5: polyhedron: ", 0), 0u) << errorOf(t1);

    scene::Tree t2;
    t2.root = t2.addLeaf(leaf(scene::Import{"/nonexistent/x.stl"}, glm::dmat4(1.0), 4));
    EXPECT_EQ(errorOf(t2), "scene.csg:4:5: /nonexistent/x.stl: cannot read mesh: no such file");

    scene::Tree t3;
    t3.root = t3.addLeaf(leaf(scene::Import{std::string(STRATA_TEST_DIR) + "/data/meshes/open_box.off"}, glm::dmat4(1.0), 9));
    EXPECT_EQ(errorOf(t3), "scene.csg:9:5: import is not a closed solid: not closed: 4 boundary edges");
}

TEST(BuildModel, MeshFileSceneIsNotNamedTwice) {
    // How an app might wrap a bare mesh file: the leaf's position is the file.
    scene::Leaf l;
    l.primitive = scene::Import{"/nonexistent/x.stl"};
    l.where = SourceLocation{"/nonexistent/x.stl", 0, 0};
    scene::Tree tree;
    tree.root = tree.addLeaf(l);
    EXPECT_EQ(errorOf(tree), "/nonexistent/x.stl: cannot read mesh: no such file");
}

TEST(BuildModel, ImportedMeshIsTransformed) {
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(scene::Import{std::string(STRATA_TEST_DIR) + "/data/meshes/cube.obj"},
                                  glm::scale(glm::dmat4(1.0), glm::dvec3(2, 2, -2))));
    const Model model = buildModel(tree);
    EXPECT_DOUBLE_EQ(signedVolume(model.leafMeshes[0]), 8.0);
    EXPECT_EQ(model.bounds.min, glm::dvec3(0, 0, -2));
    EXPECT_EQ(model.bounds.max, glm::dvec3(2, 2, 0));
}

TEST(BuildModel, FlatteningTransformGivesAnEmptyLeaf) {
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(scene::Cube{{1, 1, 1}, false}, glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, 0))));
    const Model model = buildModel(tree);
    EXPECT_TRUE(model.leafMeshes[0].triangles.empty());
    EXPECT_TRUE(model.bounds.empty());
}

TEST(BuildModel, NonFiniteTransformThrows) {
    glm::dmat4 t(1.0);
    t[3][0] = INFINITY;
    scene::Tree tree;
    tree.root = tree.addLeaf(leaf(scene::Sphere{1.0, {}}, t, 6));
    EXPECT_EQ(errorOf(tree), "scene.csg:6:5: sphere has a non-finite coordinate after its transform");
}

// A 2D union of many pieces (20 squares in a row, some apart, some
// overlapping their neighbour, one holding a square hole with a smaller
// square inside it) is united and its caps triangulated group by group of
// pieces whose boxes meet (BoxGroups.h): the extrusion must be one closed
// solid of the area a closed form gives, as if done in one sweep.
TEST(BuildModel, ManyFlatPiecesAreUnitedAndCappedGroupByGroup) {
    std::string csg = "linear_extrude(height = 2) { union() {";
    double area = 0.0;
    for (int i = 0; i < 20; ++i) {
        // Squares of side 1 at x = 1.5 i, but squares 6-8 step only 0.5 from 5 and overlap.
        const double x = i < 6 ? 1.5 * i : i <= 8 ? 7.5 + 0.5 * (i - 5) : 9.0 + 1.5 * (i - 8);
        csg += "multmatrix([[1,0,0," + std::to_string(x) + "],[0,1,0,0],[0,0,1,0],[0,0,0,1]]) square(size = [1, 1]);";
    }
    area += 5.0 + 2.5 + 11.0;  // five apart, four overlapping as one 1 x 2.5 strip, eleven apart
    // A frame of side 4 with a hole of side 2, a square of side 1 in the hole.
    csg += "multmatrix([[1,0,0,0],[0,1,0,5],[0,0,1,0],[0,0,0,1]]) difference() { square(size = [4, 4]);"
           " multmatrix([[1,0,0,1],[0,1,0,1],[0,0,1,0],[0,0,0,1]]) square(size = [2, 2]); }";
    csg += "multmatrix([[1,0,0,1.5],[0,1,0,6.5],[0,0,1,0],[0,0,0,1]]) square(size = [1, 1]);";
    area += 16.0 - 4.0 + 1.0;
    csg += "} }\n";
    std::istringstream in(csg);
    const scene::Tree tree = scene::parseCsg(in, "pieces.csg", ".");
    const Model model = buildModel(tree);
    ASSERT_EQ(model.leafMeshes.size(), 1u);
    EXPECT_TRUE(checkMesh(model.leafMeshes[0]).ok()) << checkMesh(model.leafMeshes[0]).describe();
    EXPECT_NEAR(signedVolume(model.leafMeshes[0]), 2.0 * area, 1e-9);
}
