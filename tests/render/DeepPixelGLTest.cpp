// Pixels with hundreds of surfaces. The evaluator's walk costs O(S log L) loop
// iterations for S surfaces of L live operands, well inside llvmpipe's limit
// (it ends all loops of an invocation after 65535 iterations) for these; a
// pixel that did not fit would have to be reported, never drawn wrong.
// Checked against the CPU reference.

#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"

using namespace strata;

namespace {

// The intersection of `count` spheres (r = 5, $fn = 32) at seeded offsets of
// up to 0.5: a pixel near the result's silhouette has up to 2 * count surfaces.
scene::Tree intersectionOfSpheres(int count) {
    scene::Tree tree;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-0.5, 0.5);
    std::vector<int> children;
    for (int i = 0; i < count; ++i) {
        scene::Leaf leaf;
        scene::Sphere sphere;
        sphere.r = 5.0;
        sphere.fragments.fn = 32;
        leaf.primitive = sphere;
        leaf.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(offset(rng), offset(rng), offset(rng)));
        // A copy: moving it made GCC 12 warn (wrongly) of the variant's
        // inactive Polyhedron vectors being read uninitialised.
        children.push_back(tree.addLeaf(leaf));
    }
    tree.root = tree.addNode(scene::NodeKind::Intersection, children);
    return tree;
}

}  // namespace

class DeepPixels : public ::testing::TestWithParam<int> {};

TEST_P(DeepPixels, MatchTheReference) {
    const scene::Tree tree = intersectionOfSpheres(GetParam());
    const model::Model model = model::buildModel(tree);
    camera::Camera base;
    base.width = base.height = 64;
    const camera::Camera camera = camera::cameraFromArguments({20, -30, 25, 0, 0, 0}, base);

    gpu::Context context;
    render::Renderer renderer;
    renderer.setScene(tree, model);
    const render::Frame frame = renderer.render(camera, {});
    const reference::ReferenceImage truth = reference::renderReference(tree, model, camera);

    std::size_t falseSurfaces = 0, missing = 0, covered = 0;
    for (std::size_t p = 0; p < frame.leaf.size(); ++p) {
        const bool gpu = frame.leaf[p] >= 0, ref = truth.leaf[p] >= 0;
        falseSurfaces += gpu && !ref;
        missing += ref && !gpu;
        covered += ref;
    }
    ASSERT_GT(covered, 100u) << "the scene must show something";
    EXPECT_EQ(frame.stats.unresolvedPixels, 0u);
    // One pixel of slack each way for a ray through a facet edge.
    EXPECT_LE(falseSurfaces, 1u) << "pixels drew a surface the result does not have";
    EXPECT_LE(missing, 1u);
}

// 96 spheres overran the loop limit with the first evaluator (a walk of
// O(S * L) iterations); 256 would take it about 260 000.
INSTANTIATE_TEST_SUITE_P(Spheres, DeepPixels, ::testing::Values(96, 256));
