// Peeling a non-convex operand in one geometry pass through per-pixel
// fragment lists (PeelPass::peelThroughLists) against dual depth peeling pass by pass.
// The passes are checked against analytic depths and the CPU reference
// elsewhere (RendererGLTest, the accuracy suite); here the lists must give
// the very same layers, bit for bit, and so the same frames: random unions,
// differences and intersections of operands made of up to four sphere shells
// (eight surfaces on a ray), seen from outside and from inside, with auto and
// fixed layer counts. A pixel with more fragments than a list holds must
// send its operand back to the passes; so must a small operand by default.

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "FrameCompare.h"
#include "SphereShells.h"

using namespace strata;
using scene::NodeKind;

namespace {

// `operands` leaves, each 1 to 4 sphere shells near the origin in one
// polyhedron; a difference starts with a cube that holds them.
scene::Tree shellsTree(NodeKind kind, int operands, std::mt19937& rng) {
    std::uniform_real_distribution<double> pos(-0.8, 0.8), radius(0.35, 0.6);
    scene::Tree tree;
    std::vector<int> children;
    if (kind == NodeKind::Difference) {
        scene::Leaf cube;
        cube.primitive = scene::Cube{{2.4, 2.4, 2.4}, true};
        children.push_back(tree.addLeaf(std::move(cube)));
    }
    for (int i = 0; i < operands; ++i) {
        std::vector<glm::dvec3> centres(1 + rng() % 4);
        for (glm::dvec3& c : centres) c = {pos(rng), pos(rng), pos(rng)};
        scene::Leaf leaf;
        leaf.primitive = test::sphereShells(centres, kind == NodeKind::Intersection ? 0.9 : radius(rng), 12);
        children.push_back(tree.addLeaf(std::move(leaf)));
    }
    tree.root = tree.addNode(kind, children);
    return tree;
}

// 0: outside, perspective; 1: outside, orthographic; 2: inside, the near
// plane cutting shells.
camera::Camera testCamera(int which, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    glm::dvec3 dir{unit(rng), unit(rng), 0.6};
    dir = glm::normalize(dir);
    camera::Camera camera;
    camera.width = 72;
    camera.height = 56;
    camera.center = glm::dvec3(0.0);
    camera.eye = dir * 7.0;
    camera.fovDegrees = 30.0;
    if (which == 1) camera.projection = camera::Projection::Orthographic;
    if (which == 2) {
        camera.eye = dir * 0.3;
        camera.center = camera.eye - dir;
        camera.fovDegrees = 80.0;
    }
    return camera;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Frames equal bit for bit: AOVs, layers per leaf and, where kept, every peeled layer.
void expectSame(const render::Frame& lists, const render::Frame& passes, const std::string& what) {
    ASSERT_EQ(lists.leaf.size(), passes.leaf.size()) << what;
    EXPECT_EQ(test::pixelsDiffering(lists, passes), 0u) << what;
    EXPECT_EQ(lists.stats.layersPerLeaf, passes.stats.layersPerLeaf) << what;
    ASSERT_EQ(lists.peelLayers.size(), passes.peelLayers.size()) << what;
    for (std::size_t i = 0; i < lists.peelLayers.size(); ++i) {
        const render::PeelLayerImage& a = lists.peelLayers[i];
        const render::PeelLayerImage& b = passes.peelLayers[i];
        EXPECT_EQ(a.leaf, b.leaf) << what;
        EXPECT_EQ(a.layer, b.layer) << what;
        EXPECT_TRUE(sameBits(a.nearDepth, b.nearDepth) && sameBits(a.farDepth, b.farDepth))
            << what << ": leaf " << a.leaf << " layer " << a.layer;
    }
}

}  // namespace

TEST(FragmentLists, GiveTheLayersOfDualPeeling) {
    gpu::Context context;
    render::Renderer renderer;
    std::mt19937 rng(20261123u);
    int listed = 0, deeper = 0, listPasses = 0, peelPasses = 0;
    std::size_t covered = 0;
    for (NodeKind kind : {NodeKind::Difference, NodeKind::Union, NodeKind::Intersection}) {
        for (int s = 0; s < 2; ++s) {
            const scene::Tree tree = shellsTree(kind, kind == NodeKind::Intersection ? 2 : 3, rng);
            const model::Model model = model::buildModel(tree);
            renderer.setScene(tree, model);
            for (int which = 0; which < 3; ++which) {
                const camera::Camera view = testCamera(which, rng);
                for (int layers : {0, 1, 3}) {
                    for (bool keep : {false, true}) {
                        render::RenderSettings settings;
                        settings.fragmentListTriangles = 0;  // every non-convex operand, however small
                        settings.layers = layers;
                        settings.keepPeelLayers = keep;
                        const render::Frame lists = renderer.render(view, settings);
                        settings.fragmentListTriangles = -1;
                        const render::Frame passes = renderer.render(view, settings);
                        const std::string what = std::string(scene::kindName(kind)) + ", scene " +
                                                 std::to_string(s) + ", camera " + std::to_string(which) +
                                                 ", layers " + std::to_string(layers) + (keep ? ", kept" : "");
                        expectSame(lists, passes, what);
                        EXPECT_EQ(passes.stats.listPeeledOperands, 0) << what;
                        listed += lists.stats.listPeeledOperands;
                        listPasses += lists.stats.peelPasses;
                        peelPasses += passes.stats.peelPasses;
                        covered += lists.stats.coveredPixels;
                        for (int n : lists.stats.layersPerLeaf) deeper += n > 2 ? 1 : 0;
                    }
                }
            }
        }
    }
    EXPECT_GT(covered, 0u);
    EXPECT_GT(listed, 0) << "the lists must have been used";
    EXPECT_GT(deeper, 0) << "some operands must have needed more than two layers";
    EXPECT_LT(listPasses, peelPasses);
}

TEST(FragmentLists, AFullListFallsBackToPasses) {
    // A slab minus shells stacked on the view axis: the centre ray meets two
    // surfaces per shell. Four shells fill a list of eight exactly; five
    // overflow it, and the operand is peeled pass by pass (after the
    // collecting pass that found out).
    gpu::Context context;
    render::Renderer renderer;
    camera::Camera view;
    view.width = view.height = 48;
    view.eye = {0.0, 0.0, 9.0};
    view.center = {0.0, 0.0, 0.0};
    for (int shells : {4, 5}) {
        std::vector<glm::dvec3> centres;
        for (int i = 0; i < shells; ++i) centres.push_back({0.0, 0.0, 1.0 - 0.9 * i});
        scene::Tree tree;
        scene::Leaf slab, stack;
        slab.primitive = scene::Cube{{4.0, 4.0, 6.0}, true};
        stack.primitive = test::sphereShells(centres, 0.4, 16);
        tree.root = tree.addNode(NodeKind::Difference, {tree.addLeaf(std::move(slab)), tree.addLeaf(std::move(stack))});
        const model::Model model = model::buildModel(tree);
        renderer.setScene(tree, model);
        render::RenderSettings settings;
        settings.fragmentListTriangles = 0;
        settings.keepPeelLayers = true;
        const render::Frame lists = renderer.render(view, settings);
        settings.fragmentListTriangles = -1;
        const render::Frame passes = renderer.render(view, settings);
        const std::string what = std::to_string(shells) + " shells";
        expectSame(lists, passes, what);
        EXPECT_EQ(lists.stats.layersPerLeaf[1], shells) << what;
        EXPECT_EQ(lists.stats.listPeeledOperands, shells == 4 ? 1 : 0) << what;
        EXPECT_EQ(lists.stats.peelPasses, shells == 4 ? 1 + 1 : 1 + 1 + shells) << what;
    }
}

TEST(FragmentLists, AreForOperandsOfManyTriangles) {
    // A cube minus two operands of two 12-gon shells each (a few hundred
    // triangles): peeled pass by pass unless the threshold is lowered.
    gpu::Context context;
    render::Renderer renderer;
    scene::Tree tree;
    scene::Leaf cube, left, right;
    cube.primitive = scene::Cube{{2.4, 2.4, 2.4}, true};
    left.primitive = test::sphereShells({{-0.6, 0.0, 0.5}, {-0.6, 0.0, -0.5}}, 0.4, 12);
    right.primitive = test::sphereShells({{0.6, 0.0, 0.5}, {0.6, 0.0, -0.5}}, 0.4, 12);
    tree.root = tree.addNode(NodeKind::Difference, {tree.addLeaf(std::move(cube)), tree.addLeaf(std::move(left)),
                                                    tree.addLeaf(std::move(right))});
    renderer.setScene(tree, model::buildModel(tree));
    std::mt19937 rng(7u);
    const camera::Camera view = testCamera(0, rng);
    render::RenderSettings settings;
    EXPECT_EQ(renderer.render(view, settings).stats.listPeeledOperands, 0);
    settings.fragmentListTriangles = 100;
    EXPECT_EQ(renderer.render(view, settings).stats.listPeeledOperands, 2);
}

TEST(FragmentLists, TheirImagesLeaveNothingOutsideLaterBudgets) {
    // The lists' images outlive a frame. A later frame that collects
    // nothing must let them go, and one of a smaller size must not keep
    // the larger pair: either would hold memory its budget does not count.
    gpu::Context context;
    render::Renderer renderer, fresh;
    std::mt19937 rng(5u);
    const scene::Tree tree = shellsTree(NodeKind::Difference, 3, rng);
    const model::Model model = model::buildModel(tree);
    renderer.setScene(tree, model);
    fresh.setScene(tree, model);
    camera::Camera large = testCamera(0, rng);
    large.width = 144;
    large.height = 112;
    render::RenderSettings lists;
    lists.fragmentListTriangles = 0;
    ASSERT_GT(renderer.render(large, lists).stats.listPeeledOperands, 0);

    // Passes only, in a budget that holds their layers and no lists.
    render::RenderSettings passes;
    passes.fragmentListTriangles = -1;
    passes.memoryBudget = fresh.render(large, passes).stats.textureBytes;
    const render::Frame after = renderer.render(large, passes);
    EXPECT_EQ(after.stats.listPeeledOperands, 0);
    EXPECT_LE(after.stats.textureBytes, passes.memoryBudget);

    // Lists again, then at a quarter of the size in the budget that a
    // renderer which never drew the large frame needs.
    renderer.render(large, lists);
    camera::Camera small = large;
    small.width /= 2;
    small.height /= 2;
    render::Renderer smallOnly;
    smallOnly.setScene(tree, model);
    const render::Frame wanted = smallOnly.render(small, lists);
    ASSERT_GT(wanted.stats.listPeeledOperands, 0);
    render::RenderSettings tight = lists;
    tight.memoryBudget = wanted.stats.textureBytes;
    const render::Frame got = renderer.render(small, tight);
    EXPECT_EQ(got.stats.listPeeledOperands, wanted.stats.listPeeledOperands);
    EXPECT_EQ(got.stats.tiles, 1);
    EXPECT_LE(got.stats.textureBytes, tight.memoryBudget);
    EXPECT_EQ(test::pixelsDiffering(got, wanted), 0u);
}
