// The patches of one cell over all 256 corner configurations: what the
// contouring's manifold guarantee rests on.

#include <gtest/gtest.h>

#include <bit>

#include "CellTopology.h"

using namespace strata::contour;

namespace {

constexpr int kConfigs = 256;

int changingEdges(std::uint8_t config) {
    int n = 0;
    for (int e = 0; e < kCellEdges; ++e) n += edgeChangesSign(config, e) ? 1 : 0;
    return n;
}

}  // namespace

TEST(ContourCellTopology, NumberingRoundTrips) {
    for (int c = 0; c < kCellCorners; ++c) EXPECT_EQ(cornerAt(cornerOffset(c)), c);
    for (int e = 0; e < kCellEdges; ++e) {
        EXPECT_EQ(edgeAt(edgeAxis(e), edgeStart(e)), e);
        EXPECT_EQ(edgeStart(e)[edgeAxis(e)], 0);
    }
}

TEST(ContourCellTopology, EveryChangingEdgeIsInOnePatchAndEveryPatchHasThreeEdgesAtLeast) {
    for (int c = 0; c < kConfigs; ++c) {
        const auto config = std::uint8_t(c);
        const CellPatches& patches = cellPatches(config, 0);
        std::vector<int> edgesOf(std::size_t(patches.count), 0);
        for (int e = 0; e < kCellEdges; ++e) {
            EXPECT_EQ(patches.patchOfEdge[e] >= 0, edgeChangesSign(config, e)) << c << " " << e;
            if (patches.patchOfEdge[e] >= 0) ++edgesOf[std::size_t(patches.patchOfEdge[e])];
        }
        for (int n : edgesOf) EXPECT_GE(n, 3) << "config " << c;
        EXPECT_EQ(patches.count == 0, changingEdges(config) == 0);
    }
}

TEST(ContourCellTopology, KnownCases) {
    EXPECT_EQ(cellPatches(0x01, 0).count, 1);  // one corner cut off
    EXPECT_EQ(cellPatches(0x03, 0).count, 1);  // an edge
    EXPECT_EQ(cellPatches(0x0f, 0).count, 1);  // half the cell
    // Two inside corners diagonal on the low z face: the default pairing
    // keeps them apart (two patches), the flipped one joins them.
    const std::uint8_t diagonal = 0x01 | 0x08;
    const int lowZ = 4;
    ASSERT_TRUE(ambiguousFace(diagonal, lowZ));
    EXPECT_EQ(cellPatches(diagonal, 0).count, 2);
    EXPECT_EQ(cellPatches(diagonal, std::uint8_t(1 << lowZ)).count, 1);
    // Opposite corners of the cube: no face is ambiguous.
    EXPECT_EQ(cellPatches(0x01 | 0x80, 0).count, 2);
}

// The flip rule of the contouring: a face is flipped when both its cells
// join its two segments in one patch. That is sound without iterating only
// because no cell has two such faces and a flip always separates.
TEST(ContourCellTopology, AFlipSeparatesTheSegmentsItWasFor) {
    int joinedConfigs = 0;
    for (int c = 0; c < kConfigs; ++c) {
        const auto config = std::uint8_t(c);
        const std::uint8_t joined = facesJoinedInOnePatch(config);
        EXPECT_LE(std::popcount(joined), 1) << "config " << c;
        if (joined == 0) continue;
        ++joinedConfigs;
        for (int f = 0; f < kCellFaces; ++f) {
            EXPECT_FALSE(faceSegmentsInOnePatch(config, f, joined)) << "config " << c << " face " << f;
        }
        EXPECT_EQ(cellPatches(config, joined).count, cellPatches(config, 0).count + 1);
    }
    EXPECT_GT(joinedConfigs, 0);
}
