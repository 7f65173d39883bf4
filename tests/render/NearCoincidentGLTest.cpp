// Surfaces that come close without being one: the `near_*` models of
// tests/data/coincident (a cylinder less itself moved by a hundredth, two
// cylinders a hundredth and a degree apart intersected) against OpenSCAD's
// exact result of each (NAME.off, one plain mesh, ray cast by the CPU
// reference with no tolerance at all: every crossing of its thin walls
// counts), on the GPU. Their walls
// thin out to nothing at the tips, and wherever they are thinner than the
// coincidence tolerance they vanish; with the tolerance at what a float's
// rounding needs (faces of one plane get one depth: render::FacePlanes),
// the crescent keeps every pixel the exact result has off its edges, where
// at 2^-16 of the scene's scale it loses a strip at each tip (1,660, 310
// and 384 non-edge pixels of the three views). The CPU reference is held to OpenSCAD's
// results by CoincidentExactTest.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "Compare.h"
#include "OrbitCamera.h"
#include "strata/camera/Camera.h"
#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"
#include "strata/scene/CsgParser.h"
#include "strata/scene/Tree.h"

using namespace strata;

namespace {

const std::string kDir = STRATA_TEST_DIR "/data/coincident/";

// OpenSCAD's default view of `bounds` and two more around it, one from below.
std::vector<camera::Camera> views(const mesh::Bounds& bounds) {
    camera::Camera base;
    base.width = 320;
    base.height = 240;
    const camera::Camera standard = camera::defaultCamera(bounds, base);
    auto orbit = [&](double azimuth, double elevation, camera::Projection projection) {
        return accuracy::orbit(standard, azimuth, elevation, projection);
    };
    return {standard, orbit(-151.3, 27.4, camera::Projection::Perspective),
            orbit(203.9, -33.1, camera::Projection::Orthographic)};
}

// Every hit as leaf 0: the exact mesh is one leaf, so which leaf shows is not compared.
std::vector<std::int32_t> oneLeaf(const std::vector<std::int32_t>& leaf) {
    std::vector<std::int32_t> out(leaf.size());
    std::transform(leaf.begin(), leaf.end(), out.begin(), [](std::int32_t l) { return l >= 0 ? 0 : -1; });
    return out;
}

}  // namespace

class NearCoincidentGL : public ::testing::TestWithParam<std::string> {
protected:
    static void SetUpTestSuite() { context_ = std::make_unique<gpu::Context>(); }
    static void TearDownTestSuite() { context_.reset(); }
    static std::unique_ptr<gpu::Context> context_;
};

std::unique_ptr<gpu::Context> NearCoincidentGL::context_;

TEST_P(NearCoincidentGL, GpuMatchesOpenScadsExactResult) {
    const std::string name = GetParam();
    const scene::Tree tree = scene::parseCsgFile(kDir + name + ".csg");
    const model::Model model = model::buildModel(tree);
    const scene::Tree exactTree = scene::meshFileTree(kDir + name + ".off");
    const model::Model exactModel = model::buildModel(exactTree);
    reference::ReferenceOptions exactOptions;
    exactOptions.coincidence = false;  // every crossing of the thin walls counts
    render::Renderer renderer;
    renderer.setScene(tree, model);
    const accuracy::CompareOptions options = accuracy::optionsForScene(exactModel.bounds.diagonal());
    for (const camera::Camera& camera : views(exactModel.bounds)) {
        const render::Frame frame = renderer.render(camera, {});
        const reference::ReferenceImage exact = reference::renderReference(exactTree, exactModel, camera, exactOptions);
        const std::vector<std::int32_t> frameLeaf = oneLeaf(frame.leaf), exactLeaf = oneLeaf(exact.leaf);
        const accuracy::AovView gpu{frame.width, frame.height, frame.depth, frame.normal, frameLeaf, {}};
        const accuracy::AovView ref{exact.width, exact.height, exact.depth, exact.normal, exactLeaf, {}};
        const accuracy::CompareResult r = accuracy::compare(camera, gpu, ref, options);
        std::printf("[ near ] %-18s %s %zu of %zu non-edge pixels disagree\n", name.c_str(),
                    camera.projection == camera::Projection::Orthographic ? "o" : "p", r.nonEdge.total(),
                    r.nonEdgePixels);
        EXPECT_GT(r.coveredReference, std::size_t(camera.width * camera.height) / 10);
        EXPECT_EQ(r.nonEdge.total(), 0u) << name << ": " << r.summary();
        EXPECT_TRUE(r.edgeBoundHolds()) << name << ": " << r.summary();
    }
}

INSTANTIATE_TEST_SUITE_P(Models, NearCoincidentGL, ::testing::Values("near_crescent", "near_intersection"));
