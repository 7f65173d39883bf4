// The GPU's result peel (Renderer::sampleResult through remesh::sampleOnGpu)
// against the CPU reference (remesh::sampleWithReference) on the same grid:
// every grid line must carry the same crossings, in the same order, at the
// same place to within float depth rounding, with the same normals. The
// reference traces each ray in double precision with Embree and shares no
// code with the GPU passes but the scene and the camera's rays.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "strata/camera/ViewBounds.h"
#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/reference/RayCaster.h"
#include "strata/remesh/Remesh.h"
#include "strata/render/Renderer.h"
#include "strata/scene/CsgParser.h"

using namespace strata;

namespace {

class SamplingGLTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = std::make_unique<gpu::Context>(); }
    static void TearDownTestSuite() { context_.reset(); }

    static scene::Tree parse(const std::string& text) {
        std::istringstream in(text);
        return scene::parseCsg(in, "sampling.csg", ".");
    }

    struct Counts {
        std::size_t crossings = 0;
        std::size_t raysDiffering = 0;
        double worstPlace = 0.0;   // in cells
        double worstNormal = 0.0;  // 1 - cos of the angle
        std::size_t otherFacet = 0;  // normals more than 0.1 degrees apart
    };

    // Both samplers over `text` at `resolution`; the crossing counts of
    // every ray must agree.
    static Counts compare(const std::string& text, int resolution,
                          const render::RenderSettings& settings = render::RenderSettings{}) {
        const scene::Tree tree = parse(text);
        const model::Model model = model::buildModel(tree);
        const contour::DexelGrid grid = remesh::gridFor(camera::viewBounds(tree, model), resolution);
        render::Renderer renderer;
        renderer.setScene(tree, model);
        const contour::Dexels gpu = remesh::sampleOnGpu(renderer, grid, settings);
        const contour::Dexels cpu = remesh::sampleWithReference(reference::ReferenceScene(tree, model), grid);
        Counts counts;
        for (std::size_t a = 0; a < 3; ++a) {
            const contour::DexelRays& g = gpu.axes[a];
            const contour::DexelRays& c = cpu.axes[a];
            EXPECT_EQ(g.first.size(), c.first.size());
            for (std::size_t r = 0; r + 1 < g.first.size(); ++r) {
                const std::uint32_t n = g.first[r + 1] - g.first[r];
                if (n != c.first[r + 1] - c.first[r]) {
                    ++counts.raysDiffering;
                    continue;
                }
                for (std::uint32_t k = 0; k < n; ++k) {
                    const contour::Crossing& x = g.crossings[g.first[r] + k];
                    const contour::Crossing& y = c.crossings[c.first[r] + k];
                    EXPECT_EQ(x.entering, y.entering);
                    counts.worstPlace = std::max(counts.worstPlace, std::abs(x.at - y.at) / grid.spacing);
                    // A ray through a facet edge may see either facet: the
                    // grid is symmetric where the box is, and rays on the
                    // plane x = y run along the meridian edge at 45 degrees.
                    const double off = 1.0 - double(glm::dot(x.normal, y.normal));
                    if (off > 1.5e-6) {
                        ++counts.otherFacet;
                    } else {
                        counts.worstNormal = std::max(counts.worstNormal, off);
                    }
                    ++counts.crossings;
                }
            }
        }
        return counts;
    }

    // What the two samplers must agree on, over at least `leastCrossings`.
    static void expectAgreement(const Counts& counts, std::size_t leastCrossings) {
        EXPECT_GT(counts.crossings, leastCrossings);
        EXPECT_EQ(counts.raysDiffering, 0u);
        EXPECT_LT(counts.worstPlace, 1e-3);
        EXPECT_LT(counts.worstNormal, 1e-6);
        EXPECT_LT(counts.otherFacet, counts.crossings / 25) << counts.otherFacet;
        std::printf("%zu crossings, worst place %.2e cells, %zu on another facet\n", counts.crossings,
                    counts.worstPlace, counts.otherFacet);
    }

    static std::unique_ptr<gpu::Context> context_;
};

std::unique_ptr<gpu::Context> SamplingGLTest::context_;

TEST_F(SamplingGLTest, CubeMinusSphereMatchesTheReference) {
    const Counts counts = compare(
        "difference() { cube(size = [10, 10, 10], center = true); "
        "sphere(r = 6.5, $fn = 24); }",
        32);
    expectAgreement(counts, 1000);
}

TEST_F(SamplingGLTest, NestedShellsGiveEveryChange) {
    // Three nested shells: a ray through the middle changes six times.
    const Counts counts = compare(
        "union() { difference() { sphere(r = 10, $fn = 16); sphere(r = 8, $fn = 16); }"
        " difference() { sphere(r = 6, $fn = 16); sphere(r = 4, $fn = 16); }"
        " sphere(r = 2, $fn = 16); }",
        24);
    expectAgreement(counts, 1000);
}

TEST_F(SamplingGLTest, ManyOperandsInTilesMatchTheReference) {
    // Twelve holes: more peeled layers than the register form holds, so
    // blocks take the array form; a small memory budget cuts the frames
    // into tiles, each with rounds of its own.
    std::string text = "difference() { cube(size = [20, 20, 20], center = true); ";
    for (int i = 0; i < 12; ++i) {
        const double x = -7.0 + 1.3 * i, y = 6.0 - 1.1 * i, z = (i % 3 - 1) * 5.5;
        text += "multmatrix([[1,0,0," + std::to_string(x) + "],[0,1,0," + std::to_string(y) + "],[0,0,1," +
                std::to_string(z) + "],[0,0,0,1]]) sphere(r = 3.2, $fn = 12); ";
    }
    text += "}";
    render::RenderSettings settings;
    settings.memoryBudget = std::size_t(1) << 16;
    const Counts counts = compare(text, 40, settings);
    expectAgreement(counts, 5000);
}

}  // namespace
