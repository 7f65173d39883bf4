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
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "Compare.h"
#include "strata/camera/Camera.h"
#include "strata/geometry/Model.h"
#include "strata/gpu/Context.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"
#include "strata/scene/CsgParser.h"
#include "strata/scene/Tree.h"

using namespace strata;

namespace {

const std::string kDir = STRATA_TEST_DIR "/data/coincident/";

// OpenSCAD's default view of `bounds` and two more around it, one from below.
std::vector<render::Camera> views(const geometry::Bounds& bounds) {
    render::Camera base;
    base.width = 320;
    base.height = 240;
    const render::Camera standard = render::defaultCamera(bounds, base);
    const double distance = glm::length(standard.eye - standard.center);
    auto orbit = [&](double azimuth, double elevation, render::Projection projection) {
        const double az = azimuth * std::numbers::pi / 180.0, el = elevation * std::numbers::pi / 180.0;
        render::Camera c = standard;
        c.eye = c.center + distance * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        c.projection = projection;
        return c;
    };
    return {standard, orbit(-151.3, 27.4, render::Projection::Perspective),
            orbit(203.9, -33.1, render::Projection::Orthographic)};
}

// The exact mesh's image, its crossings taken at their exact distances (no
// tolerance): leaf 0 wherever it is hit.
reference::ReferenceImage exactImage(const reference::ReferenceScene& mesh, const render::Camera& camera) {
    reference::ReferenceImage image;
    image.width = camera.width;
    image.height = camera.height;
    const auto pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
    image.depth.assign(pixels, std::numeric_limits<float>::infinity());
    image.normal.assign(pixels, glm::vec3(0.0f));
    image.leaf.assign(pixels, -1);
    image.cut.assign(pixels, 0);
    for (int j = 0; j < camera.height; ++j) {
        for (int i = 0; i < camera.width; ++i) {
            const render::Ray ray = camera.ray(i, j);
            const reference::RayHit hit = mesh.trace(ray, 0.0, 0.0);
            if (!hit.hit()) continue;
            const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(camera.width) + i;
            image.depth[k] = static_cast<float>(camera.viewDepth(ray.origin + hit.t * ray.direction));
            image.normal[k] = glm::vec3(hit.normal);
            image.leaf[k] = 0;
        }
    }
    return image;
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
    const geometry::Model model = geometry::buildModel(tree);
    const scene::Tree exactTree = scene::meshFileTree(kDir + name + ".off");
    const geometry::Model exactModel = geometry::buildModel(exactTree);
    const reference::ReferenceScene exactScene(exactTree, exactModel);
    render::Renderer renderer;
    renderer.setScene(tree, model);
    const accuracy::CompareOptions options = accuracy::optionsForScene(exactModel.bounds.diagonal());
    for (const render::Camera& camera : views(exactModel.bounds)) {
        const render::Frame frame = renderer.render(camera, {});
        const reference::ReferenceImage exact = exactImage(exactScene, camera);
        const std::vector<std::int32_t> frameLeaf = oneLeaf(frame.leaf), exactLeaf = oneLeaf(exact.leaf);
        const accuracy::AovView gpu{frame.width, frame.height, frame.depth, frame.normal, frameLeaf, {}};
        const accuracy::AovView ref{exact.width, exact.height, exact.depth, exact.normal, exactLeaf, {}};
        const accuracy::CompareResult r = accuracy::compare(camera, gpu, ref, options);
        std::printf("[ near ] %-18s %s %zu of %zu non-edge pixels disagree\n", name.c_str(),
                    camera.projection == render::Projection::Orthographic ? "o" : "p", r.nonEdge.total(),
                    r.nonEdgePixels);
        EXPECT_GT(r.coveredReference, std::size_t(camera.width * camera.height) / 10);
        EXPECT_EQ(r.nonEdge.total(), 0u) << name << ": " << r.summary();
        EXPECT_TRUE(r.edgeBoundHolds()) << name << ": " << r.summary();
    }
}

INSTANTIATE_TEST_SUITE_P(Models, NearCoincidentGL, ::testing::Values("near_crescent", "near_intersection"));
