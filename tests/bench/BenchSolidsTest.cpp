// strata-bench's solids and scenes: closed, outward, the sizes they promise.
#include <gtest/gtest.h>

#include "CsgProduct.h"
#include "Scenes.h"
#include "Solids.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/Model.h"

using namespace strata;

namespace {

mesh::Mesh meshOf(const scene::Polyhedron& polyhedron) {
    scene::Tree tree;
    scene::Leaf leaf;
    leaf.primitive = polyhedron;
    tree.root = tree.addLeaf(std::move(leaf));
    return model::buildModel(tree).leafMeshes.at(0);  // throws unless closed and outward
}

}  // namespace

TEST(BenchSolids, TorusIsAClosedOutwardSolid) {
    const mesh::Mesh mesh = meshOf(bench::torus(1.0, 0.3, 32, 16));
    EXPECT_EQ(mesh.triangles.size(), 2u * 32 * 16);
    EXPECT_TRUE(mesh::checkMesh(mesh).ok()) << mesh::checkMesh(mesh).describe();
}

TEST(BenchSolids, TorusKnotIsAClosedOutwardSolidOfOver100kTriangles) {
    const mesh::Mesh mesh = meshOf(bench::torusKnot(3.0, 1.2, 1024, 64));
    EXPECT_EQ(mesh.triangles.size(), 131072u);
    EXPECT_TRUE(mesh::checkMesh(mesh).ok()) << mesh::checkMesh(mesh).describe();
}

TEST(BenchScenes, EverySceneBecomesOpenCsgProducts) {
    camera::Camera base;
    for (const std::string& name : bench::sceneNames()) {
        const bench::BenchScene scene = bench::makeScene(name, 3, 1, base);
        const model::Model model = model::buildModel(scene.tree);
        const bench::CsgProducts products = bench::csgProducts(scene.tree, model);
        ASSERT_TRUE(products.unavailable.empty()) << name << ": " << products.unavailable;
        ASSERT_FALSE(products.sum.products.empty()) << name;
        if (name == "deep") continue;  // its products depend on which random leaves overlap
        if (name == "blowup") {
            EXPECT_EQ(products.sum.products.size(), 8u);
            continue;
        }
        ASSERT_EQ(products.sum.products.size(), 1u) << name;
        const bench::NormalizedProduct& product = products.sum.products[0];
        if (name == "stack") {
            // Spheres whose boxes miss the slab's are pruned, as OpenSCAD prunes them.
            EXPECT_EQ(product.intersections.size(), 1u);
            EXPECT_GE(product.subtractions.size(), 1u);
            EXPECT_LE(product.subtractions.size(), 3u);
            continue;
        }
        // cheese, tori, mesh: one solid minus 3; intersection: 3 intersected.
        EXPECT_EQ(product.intersections.size(), name == "intersection" ? 3u : 1u) << name;
        EXPECT_EQ(product.subtractions.size(), name == "intersection" ? 0u : 3u) << name;
        const int last = name == "intersection" ? product.intersections.back() : product.subtractions.back();
        EXPECT_EQ(products.leaves[std::size_t(last)].convex, name != "tori") << name;
        EXPECT_FALSE(products.leaves[std::size_t(last)].positions.empty()) << name;
    }
}

TEST(BenchScenes, SingleChildGroupsAreTheirChild) {
    // OpenSCAD's export wraps objects in group() nodes of one child, and a
    // mesh file is a one-leaf tree: one product each.
    scene::Tree tree;
    scene::Leaf cube, sphere;
    cube.primitive = scene::Cube{};
    sphere.primitive = scene::Sphere{};
    const int cubeInGroup = tree.addNode(scene::NodeKind::Union, {tree.addLeaf(cube)});
    const int difference = tree.addNode(scene::NodeKind::Difference, {cubeInGroup, tree.addLeaf(sphere)});
    tree.root = tree.addNode(scene::NodeKind::Union, {difference});
    const model::Model model = model::buildModel(tree);
    const bench::CsgProducts products = bench::csgProducts(tree, model);
    ASSERT_TRUE(products.unavailable.empty()) << products.unavailable;
    ASSERT_EQ(products.sum.products.size(), 1u);
    EXPECT_EQ(products.sum.products[0].intersections, std::vector<int>{0});
    EXPECT_EQ(products.sum.products[0].subtractions, std::vector<int>{1});

    // Two objects side by side: a union of two products.
    scene::Tree two;
    two.root = two.addNode(scene::NodeKind::Union, {two.addLeaf(cube), two.addLeaf(sphere)});
    EXPECT_EQ(bench::csgProducts(two, model::buildModel(two)).sum.products.size(), 2u);
}
