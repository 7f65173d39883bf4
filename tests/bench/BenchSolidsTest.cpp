// strata-bench's solids and scenes: closed, outward, the sizes they promise.
#include <gtest/gtest.h>

#include "CsgProduct.h"
#include "Scenes.h"
#include "Solids.h"
#include "strata/geometry/MeshCheck.h"
#include "strata/geometry/Model.h"

using namespace strata;

namespace {

geometry::Mesh meshOf(const scene::Polyhedron& polyhedron) {
    scene::Tree tree;
    scene::Leaf leaf;
    leaf.primitive = polyhedron;
    tree.root = tree.addLeaf(std::move(leaf));
    return geometry::buildModel(tree).leafMeshes.at(0);  // throws unless closed and outward
}

}  // namespace

TEST(BenchSolids, TorusIsAClosedOutwardSolid) {
    const geometry::Mesh mesh = meshOf(bench::torus(1.0, 0.3, 32, 16));
    EXPECT_EQ(mesh.triangles.size(), 2u * 32 * 16);
    EXPECT_TRUE(geometry::checkMesh(mesh).ok()) << geometry::checkMesh(mesh).describe();
}

TEST(BenchSolids, TorusKnotIsAClosedOutwardSolidOfOver100kTriangles) {
    const geometry::Mesh mesh = meshOf(bench::torusKnot(3.0, 1.2, 1024, 64));
    EXPECT_EQ(mesh.triangles.size(), 131072u);
    EXPECT_TRUE(geometry::checkMesh(mesh).ok()) << geometry::checkMesh(mesh).describe();
}

TEST(BenchScenes, EveryProductSceneBecomesOpenCsgOperands) {
    render::Camera base;
    for (const std::string& name : bench::sceneNames()) {
        const bench::BenchScene scene = bench::makeScene(name, 3, 1, base);
        const geometry::Model model = geometry::buildModel(scene.tree);
        const bench::CsgProduct product = bench::csgProduct(scene.tree, model);
        if (name == "deep") {
            EXPECT_FALSE(product.notProduct.empty());
            continue;
        }
        ASSERT_TRUE(product.notProduct.empty()) << name << ": " << product.notProduct;
        EXPECT_EQ(product.operands.size(), name == "intersection" ? 3u : 4u) << name;
        EXPECT_EQ(product.operands.back().subtract, name != "intersection") << name;
        EXPECT_EQ(product.operands.back().convex, name != "tori") << name;
    }
}

TEST(BenchScenes, SingleChildGroupsAreTheirChild) {
    // OpenSCAD's export wraps objects in group() nodes of one child, and a
    // mesh file is a one-leaf tree: OpenCSG can still take them.
    scene::Tree tree;
    scene::Leaf cube, sphere;
    cube.primitive = scene::Cube{};
    sphere.primitive = scene::Sphere{};
    const int cubeInGroup = tree.addNode(scene::NodeKind::Union, {tree.addLeaf(cube)});
    const int difference = tree.addNode(scene::NodeKind::Difference, {cubeInGroup, tree.addLeaf(sphere)});
    tree.root = tree.addNode(scene::NodeKind::Union, {difference});
    const geometry::Model model = geometry::buildModel(tree);
    const bench::CsgProduct product = bench::csgProduct(tree, model);
    ASSERT_TRUE(product.notProduct.empty()) << product.notProduct;
    ASSERT_EQ(product.operands.size(), 2u);
    EXPECT_FALSE(product.operands[0].subtract);
    EXPECT_TRUE(product.operands[1].subtract);

    // Two objects side by side are a union, not a product.
    scene::Tree two;
    two.root = two.addNode(scene::NodeKind::Union, {two.addLeaf(cube), two.addLeaf(sphere)});
    EXPECT_FALSE(bench::csgProduct(two, geometry::buildModel(two)).notProduct.empty());
}
