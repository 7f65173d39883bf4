// The comparison on synthetic images whose right answer is worked out here:
// which pixels are edge pixels (the reference image's silhouettes, leaf
// boundaries, creases and facet boundaries, and nothing of the GPU image's),
// what each disagreement is counted as, and where the bounds (99.99% of
// non-edge pixels, 1% of the image on edges) cut.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "Compare.h"
#include "DiffImages.h"
#include "strata/core/Error.h"

using namespace strata;
using namespace strata::accuracy;

namespace {

constexpr int kSize = 96;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Orthographic, straight down -Z from z = 10: view depth = 10 - z.
camera::Camera topCamera(camera::Projection projection = camera::Projection::Orthographic, int size = kSize) {
    camera::Camera c;
    c.eye = {0.0, 0.0, 10.0};
    c.center = {0.0, 0.0, 0.0};
    c.projection = projection;
    c.fovDegrees = 30.0;
    c.width = size;
    c.height = size;
    return c;
}

struct Synth {
    int width, height;
    std::vector<float> depth;
    std::vector<glm::vec3> normal;
    std::vector<std::int32_t> leaf;
    std::vector<std::uint8_t> cut;  // empty: not carried

    explicit Synth(int size = kSize)
        : width(size),
          height(size),
          depth(static_cast<std::size_t>(size) * size, kInf),
          normal(static_cast<std::size_t>(size) * size, glm::vec3(0.0f)),
          leaf(static_cast<std::size_t>(size) * size, -1) {}

    std::size_t at(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
    void set(int i, int j, float z, glm::vec3 n, int id = 0) {
        depth[at(i, j)] = z;
        normal[at(i, j)] = n;
        leaf[at(i, j)] = id;
    }
    // A square [i0, i1) x [j0, j1) of one flat surface facing the camera.
    Synth& square(int i0, int i1, int j0, int j1, float z = 10.0f, glm::vec3 n = {0, 0, 1}, int id = 0) {
        for (int j = j0; j < j1; ++j)
            for (int i = i0; i < i1; ++i) set(i, j, z, n, id);
        return *this;
    }
    AovView view() const { return {width, height, depth, normal, leaf, cut}; }
};

CompareOptions options() {
    CompareOptions o;
    o.depthTolerance = 1e-3;
    return o;
}

glm::vec3 tilted(double degrees) {
    const double a = degrees * std::numbers::pi / 180.0;
    return {static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a))};
}

}  // namespace

TEST(AccuracyCompare, IdenticalImagesAgreeWithTheSilhouetteCountedApart) {
    Synth a;
    a.square(20, 80, 10, 70);
    const CompareResult r = compare(topCamera(), a.view(), a.view(), options());
    EXPECT_TRUE(r.passed()) << r.summary();
    EXPECT_EQ(r.nonEdge.total(), 0u);
    EXPECT_EQ(r.edge.total(), 0u);
    // The band on both sides of the square's outline: 62x62 - 58x58 pixels.
    EXPECT_EQ(r.edgePixels, 62u * 62u - 58u * 58u);
    EXPECT_EQ(r.coveredGpu, 60u * 60u);
    EXPECT_EQ(r.agreement(), 1.0);
}

TEST(AccuracyCompare, ASilhouetteOnePixelOffDisagreesOnlyOnEdgePixels) {
    Synth ref, gpu;
    ref.square(20, 80, 10, 70);
    gpu.square(21, 80, 10, 70);  // the left column missing: 60 pixels
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.total(), 0u);
    EXPECT_EQ(r.edge.coverage, 60u);
    EXPECT_TRUE(r.passed()) << r.summary();  // 60 / 9216 = 0.65% <= 1%
}

TEST(AccuracyCompare, EdgeDisagreementsAboveOnePercentOfTheImageFail) {
    Synth ref, gpu;
    ref.square(20, 80, 10, 70);
    gpu.square(19, 81, 9, 71);  // one pixel larger all round: 62^2 - 60^2 = 244 pixels, 2.6%
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.total(), 0u);
    EXPECT_EQ(r.edge.coverage, 244u);
    EXPECT_TRUE(r.agreementHolds());
    EXPECT_FALSE(r.edgeBoundHolds());
    EXPECT_FALSE(r.passed());
}

TEST(AccuracyCompare, AWrongRegionFailsByItsInteriorPixels) {
    Synth ref, gpu;
    ref.square(0, kSize, 0, kSize);
    gpu.square(0, kSize, 0, kSize).square(30, 50, 30, 50, 11.0f);  // a 20x20 patch one unit too deep
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    // The patch's outline is a depth step in the GPU image only: edges are
    // the reference's, so all 400 pixels count, its outline too.
    EXPECT_EQ(r.edgePixels, 0u);
    EXPECT_EQ(r.nonEdge.depth, 20u * 20u);
    EXPECT_EQ(r.edge.depth, 0u);
    EXPECT_FALSE(r.agreementHolds());
    EXPECT_FALSE(r.passed());
    EXPECT_NEAR(r.maxDepthError, 1.0, 1e-6);
}

TEST(AccuracyCompare, OnePixelInTenThousandIsTheAgreementBound) {
    // 200x200: 40000 non-edge pixels, of which 4 may disagree (99.99%), 5 not.
    constexpr int kBig = 200;
    const camera::Camera cam = topCamera(camera::Projection::Orthographic, kBig);
    Synth ref(kBig), gpu(kBig);
    ref.square(0, kBig, 0, kBig);
    gpu.square(0, kBig, 0, kBig);
    // Normals off by less than the crease angle of a real edge but more than
    // the tolerance, then depths off: single wrong pixels of the GPU image
    // make no edges of their own.
    for (int k = 0; k < 2; ++k) gpu.set(10 + 40 * k, 40, 10.0f, tilted(3.0), 0);
    for (int k = 0; k < 2; ++k) gpu.set(10 + 40 * k, 120, 10.5f, {0, 0, 1}, 0);
    CompareResult r = compare(cam, gpu.view(), ref.view(), options());
    EXPECT_EQ(r.edgePixels, 0u);
    EXPECT_EQ(r.nonEdge.normal, 2u);
    EXPECT_EQ(r.nonEdge.depth, 2u);
    EXPECT_EQ(r.nonEdgeNeighbourNormal, 0u);  // no neighbour has the tilted normal
    EXPECT_TRUE(r.passed()) << r.summary();  // 4 of 40000 = 0.010%
    gpu.set(150, 150, 10.0f, tilted(3.0), 0);
    r = compare(cam, gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.normal, 3u);
    EXPECT_FALSE(r.passed()) << r.summary();  // 0.0125%
    // At 96x96 the bound leaves no disagreement at all.
    Synth small, one;
    small.square(0, kSize, 0, kSize);
    one.square(0, kSize, 0, kSize).set(40, 40, 10.0f, tilted(3.0), 0);
    EXPECT_FALSE(compare(topCamera(), one.view(), small.view(), options()).passed());
}

TEST(AccuracyCompare, ASpeckledGpuImageFailsWhateverEdgesItMakes) {
    // Coincident faces of two leaves fought over by the GPU: every fifth
    // pixel of a 30x30 patch shows the other leaf, a little deeper, with its
    // normal turned 90 degrees, or nothing (a pinhole). In the GPU image each
    // speckle is a silhouette, a leaf boundary, a crease and a depth step at
    // once, so edges taken from either image would excuse every one of them
    // and its neighbours; edges come from the reference, which has none here.
    Synth ref, gpu;
    ref.square(0, kSize, 0, kSize, 10.0f, {0, 0, 1}, 0);
    gpu = ref;
    std::size_t speckles = 0;
    for (int j = 30; j < 60; ++j) {
        for (int i = 30; i < 60; ++i) {
            if ((i + 2 * j) % 5 != 0) continue;
            if (speckles % 3 == 2) {
                gpu.set(i, j, kInf, glm::vec3(0.0f), -1);
            } else {
                gpu.set(i, j, 10.0f + (speckles % 3 == 0 ? 0.0f : 0.5f), speckles % 3 == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1), 1);
            }
            ++speckles;
        }
    }
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.edgePixels, 0u);
    EXPECT_EQ(r.nonEdge.total(), speckles);
    EXPECT_GT(r.nonEdge.coverage, 0u);
    EXPECT_GT(r.nonEdge.depth, 0u);
    EXPECT_GT(r.nonEdge.normal, 0u);
    EXPECT_FALSE(r.agreementHolds()) << r.summary();
    EXPECT_FALSE(r.passed());
    // The GPU image's own edges would have covered the whole patch.
    const std::vector<EdgeKind> own = edgeMask(topCamera(), gpu.view(), options());
    std::size_t hidden = 0;
    for (std::size_t k = 0; k < own.size(); ++k)
        hidden += (own[k] == EdgeKind::Edge && r.verdict[k] != Verdict::Agree) ? 1 : 0;
    EXPECT_EQ(hidden, speckles);
}

TEST(AccuracyCompare, AOnePixelFacetBoundarySwapIsAnEdgeAndPasses) {
    // A faceted cylinder seen from the side: eight facets of 12 columns, their
    // normals 7.5 degrees apart. Where a pixel centre lies on a facet boundary
    // the rasterizer may give it to one facet and the exact ray test to the
    // other: the GPU shows a neighbouring facet's normal at a few such pixels.
    Synth ref;
    for (int f = 0; f < 8; ++f) ref.square(12 * f, 12 * f + 12, 0, kSize, 10.0f, tilted(-26.25 + 7.5 * f));
    Synth gpu = ref;
    gpu.set(12, 30, 10.0f, tilted(-26.25));       // facet 1's first column takes facet 0's normal
    gpu.set(35, 31, 10.0f, tilted(-26.25 + 22.5));  // facet 2's last column takes facet 3's
    for (int j = 60; j < 64; ++j) gpu.set(72, j, 10.0f, tilted(-26.25 + 37.5));  // a run of four
    CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    // Both columns beside each of the seven facet boundaries are beside one;
    // the six swapped pixels among them are edge pixels.
    EXPECT_EQ(r.facetBoundaryPixels, 7u * 2u * kSize);
    EXPECT_EQ(r.facetSwaps, 6u);
    EXPECT_EQ(r.edgePixels, 6u);
    EXPECT_EQ(r.nonEdge.total(), 0u);
    EXPECT_EQ(r.edge.normal, 6u);
    EXPECT_EQ(r.edgeNeighbourNormal, 6u);
    EXPECT_TRUE(r.passed()) << r.summary();
    // The same wrong normal two columns from the boundary is no edge's: it fails.
    Synth away = gpu;
    away.set(14, 50, 10.0f, tilted(-26.25));
    r = compare(topCamera(), away.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.normal, 1u);
    EXPECT_EQ(r.nonEdgeNeighbourNormal, 0u);  // no neighbour of (14, 50) has facet 0's normal
    EXPECT_FALSE(r.passed()) << r.summary();
    // A facet that no neighbouring pixel shows (a sliver, or a vertex where
    // several facets meet), 12 degrees off, beside a boundary: a facet swap.
    Synth sliver = gpu;
    sliver.set(24, 80, 10.0f, tilted(-11.25 + 12.0));
    r = compare(topCamera(), sliver.view(), ref.view(), options());
    EXPECT_EQ(r.facetSwaps, 7u);
    EXPECT_EQ(r.edgeNeighbourNormal, 6u);
    EXPECT_TRUE(r.passed()) << r.summary();
    // Beside a facet boundary only the facet may differ: a wrong depth, a
    // normal further off than the crease angle (a face turned the wrong
    // way), or the neighbouring facet's normal on another leaf counts as a
    // non-edge disagreement.
    struct Wrong {
        float z;
        glm::vec3 n;
        int leaf;
        Verdict verdict;
    };
    for (const Wrong& w : {Wrong{10.5f, tilted(-11.25), 0, Verdict::Depth}, Wrong{10.0f, tilted(60.0), 0, Verdict::Normal},
                           Wrong{10.0f, -tilted(-11.25), 0, Verdict::Normal}, Wrong{10.0f, tilted(-18.75), 1, Verdict::Normal}}) {
        Synth beside = gpu;
        beside.set(24, 80, w.z, w.n, w.leaf);
        r = compare(topCamera(), beside.view(), ref.view(), options());
        EXPECT_EQ(r.verdict[beside.at(24, 80)], w.verdict);
        EXPECT_EQ(r.nonEdge.total(), 1u);
        EXPECT_EQ(r.facetSwaps, 6u);
        EXPECT_FALSE(r.passed()) << r.summary();
    }
}

TEST(AccuracyCompare, DepthIsJudgedAgainstTheTolerance) {
    Synth ref, gpu, far;
    ref.square(0, kSize, 0, kSize);
    gpu.square(0, kSize, 0, kSize, 10.0f + 0.0009f);
    far.square(0, kSize, 0, kSize, 10.0f + 0.0012f);
    const CompareResult near = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_TRUE(near.passed()) << near.summary();
    const CompareResult off = compare(topCamera(), far.view(), ref.view(), options());
    EXPECT_EQ(off.nonEdge.depth, std::size_t(kSize * kSize));
    EXPECT_FALSE(off.passed());
}

TEST(AccuracyCompare, NormalsWithinOneDegreeAgree) {
    Synth ref, half, two;
    ref.square(0, kSize, 0, kSize);
    half.square(0, kSize, 0, kSize, 10.0f, tilted(0.5));
    two.square(0, kSize, 0, kSize, 10.0f, tilted(2.0));
    EXPECT_TRUE(compare(topCamera(), half.view(), ref.view(), options()).passed());
    const CompareResult r = compare(topCamera(), two.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.normal, std::size_t(kSize * kSize));
    EXPECT_NEAR(r.maxNormalErrorDegrees, 2.0, 1e-3);
}

TEST(AccuracyCompare, LeafIdsMustMatch) {
    Synth ref, gpu;
    ref.square(0, kSize, 0, kSize, 10.0f, {0, 0, 1}, 3);
    gpu.square(0, kSize, 0, kSize, 10.0f, {0, 0, 1}, 4);
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.leaf, std::size_t(kSize * kSize));
    EXPECT_FALSE(r.passed());
}

TEST(AccuracyCompare, TheCutBitIsComparedWhereBothImagesCarryIt) {
    Synth ref, gpu;
    ref.square(0, kSize, 0, kSize, 10.0f, {0, 0, 1}, 2);
    ref.cut.assign(kSize * kSize, 1);
    gpu = ref;
    // A 20x20 patch shown as the leaf's own face where the reference cuts it:
    // the same depth, normal and leaf, another colour. No edge: all 400 count.
    for (int j = 30; j < 50; ++j)
        for (int i = 30; i < 50; ++i) gpu.cut[gpu.at(i, j)] = 0;
    CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.cut, 400u);
    EXPECT_EQ(r.nonEdge.total(), 400u);
    EXPECT_EQ(r.verdict[gpu.at(40, 40)], Verdict::Cut);
    EXPECT_EQ(r.edgePixels, 0u);
    EXPECT_FALSE(r.passed());
    // Either image without the bit: it is not compared.
    gpu.cut.clear();
    r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.nonEdge.total(), 0u);
    EXPECT_TRUE(r.passed()) << r.summary();
    // A bit per pixel or none.
    gpu.cut.assign(10, 0);
    EXPECT_THROW(compare(topCamera(), gpu.view(), ref.view(), options()), Error);
}

TEST(AccuracyCompare, AMissMustHaveInfiniteDepth) {
    Synth ref, gpu;
    gpu.depth[gpu.at(3, 3)] = 5.0f;  // leaf -1 but a finite depth
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    EXPECT_EQ(r.verdict[gpu.at(3, 3)], Verdict::Depth);
}

TEST(AccuracyCompare, ADepthStepOnOneLeafWithOneNormalIsAnEdge) {
    // Two parallel faces of one leaf (a comb's teeth) at depths 10 and 12, the
    // step between columns 47 and 48.
    Synth a;
    a.square(0, 48, 0, kSize, 10.0f).square(48, kSize, 0, kSize, 12.0f);
    const std::vector<EdgeKind> mask = edgeMask(topCamera(), a.view(), options());
    for (int i = 0; i < kSize; ++i) {
        EXPECT_EQ(mask[a.at(i, 50)], (i == 47 || i == 48) ? EdgeKind::Edge : EdgeKind::None) << "column " << i;
    }
}

TEST(AccuracyCompare, FacetBoundariesAboveTheNormalToleranceCreasesAboveThirtyDegrees) {
    // 22.5 degrees: the facet angle of a $fn = 16 curve.
    for (double degrees : {0.5, 2.0, 22.5, 40.0}) {
        Synth a;
        // Two planes meeting in the line x = 0 (between columns 47 and 48):
        // z = 0 for x < 0, z = x tan(a) for x > 0, with their normals.
        const camera::Camera cam = topCamera();
        const double t = std::tan(degrees * std::numbers::pi / 180.0);
        for (int j = 0; j < kSize; ++j) {
            for (int i = 0; i < kSize; ++i) {
                const camera::Ray ray = cam.ray(i, j);
                const double x = ray.origin.x;
                const double z = x > 0 ? x * t : 0.0;
                a.set(i, j, static_cast<float>(10.0 - z), x > 0 ? tilted(-degrees) : glm::vec3(0, 0, 1), 0);
            }
        }
        const std::vector<EdgeKind> mask = edgeMask(cam, a.view(), options());
        const EdgeKind expected = degrees > 30.0 ? EdgeKind::Edge
                                  : degrees > 1.0 ? EdgeKind::FacetBoundary
                                                  : EdgeKind::None;
        EXPECT_EQ(mask[a.at(47, 20)], expected) << degrees;
        EXPECT_EQ(mask[a.at(48, 20)], expected) << degrees;
        EXPECT_EQ(mask[a.at(30, 20)], EdgeKind::None) << degrees;
    }
}

TEST(AccuracyCompare, AGrazingPlaneIsNotAnEdge) {
    // A plane seen at 85 degrees from its normal in perspective: its depth
    // changes fast from pixel to pixel, but every point lies on one plane.
    camera::Camera cam = topCamera(camera::Projection::Perspective);
    const glm::dvec3 n = glm::normalize(glm::dvec3(std::sin(85.0 * std::numbers::pi / 180.0), 0.0,
                                                   std::cos(85.0 * std::numbers::pi / 180.0)));
    const glm::dvec3 p0(0.0, 0.0, 0.0);
    Synth a;
    for (int j = 0; j < kSize; ++j) {
        for (int i = 0; i < kSize; ++i) {
            const camera::Ray ray = cam.ray(i, j);
            const double denom = glm::dot(ray.direction, n);
            const double t = glm::dot(p0 - ray.origin, n) / denom;
            if (t <= 0.0 || denom >= 0.0) continue;  // only where the plane faces the eye
            a.set(i, j, static_cast<float>(cam.viewDepth(ray.origin + t * ray.direction)), glm::vec3(n), 0);
        }
    }
    const std::vector<EdgeKind> mask = edgeMask(cam, a.view(), options());
    std::size_t edges = 0, covered = 0;
    for (int j = 1; j + 1 < kSize; ++j) {
        for (int i = 1; i + 1 < kSize; ++i) {
            const bool coveredHere = a.leaf[a.at(i, j)] >= 0;
            bool neighbourMiss = false;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) neighbourMiss |= a.leaf[a.at(i + di, j + dj)] < 0;
            if (coveredHere && !neighbourMiss) {
                ++covered;
                edges += mask[a.at(i, j)] != EdgeKind::None ? 1 : 0;
            }
        }
    }
    EXPECT_GT(covered, 1000u);
    EXPECT_EQ(edges, 0u);
}

TEST(AccuracyCompare, RefusesImagesOfAnotherSize) {
    Synth a;
    camera::Camera cam = topCamera();
    cam.width = 95;
    EXPECT_THROW(compare(cam, a.view(), a.view(), options()), Error);
    EXPECT_THROW(compare(topCamera(), a.view(), a.view(), CompareOptions{}), Error);  // no depth tolerance
}

TEST(AccuracyCompare, OptionsForASceneUseOneTenThousandthOfTheDiagonal) {
    const CompareOptions o = optionsForScene(34.6);
    EXPECT_DOUBLE_EQ(o.depthTolerance, 34.6e-4);
    EXPECT_EQ(o.normalToleranceDegrees, 1.0);
    EXPECT_EQ(o.creaseDegrees, 30.0);
    EXPECT_EQ(o.facetDegrees, 1.0);
    EXPECT_EQ(o.minAgreement, 0.9999);
    EXPECT_EQ(o.maxEdgeDisagreement, 0.01);
}

TEST(AccuracyCompare, FailureImagesAreWrittenAndNamed) {
    Synth ref, gpu;
    ref.square(0, kSize, 0, kSize);
    gpu.square(0, kSize, 0, kSize).square(30, 50, 30, 50, 11.0f);
    gpu.square(60, 70, 60, 70, kInf, glm::vec3(0.0f), -1);  // a hole: coverage
    const CompareResult r = compare(topCamera(), gpu.view(), ref.view(), options());
    const RgbaImage heat = heatMap(topCamera(), gpu.view(), ref.view(), r);
    ASSERT_EQ(heat.rgba.size(), std::size_t(kSize * kSize * 4));
    const std::size_t hole = 4 * gpu.at(65, 65), deep = 4 * gpu.at(40, 40);
    EXPECT_EQ(heat.rgba[hole + 0], 255);  // red: coverage
    EXPECT_LT(heat.rgba[hole + 1], 64);
    EXPECT_EQ(heat.rgba[deep + 0], 255);  // yellow-orange: depth
    EXPECT_GT(heat.rgba[deep + 1], 100);
    EXPECT_EQ(heat.rgba[deep + 2], 0);

    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "strata_accuracy_compare_test";
    std::filesystem::remove_all(dir);
    const ComparisonImages paths =
        writeComparisonImages((dir / "sub" / "case").string(), topCamera(), gpu.view(), ref.view(), r);
    for (const std::string& p : {paths.gpu, paths.reference, paths.diff, paths.strip}) {
        EXPECT_TRUE(std::filesystem::exists(p)) << p;
        EXPECT_GT(std::filesystem::file_size(p), 100u) << p;
    }
    EXPECT_EQ(paths.diff, (dir / "sub" / "case-diff.png").string());
    std::filesystem::remove_all(dir);
}
