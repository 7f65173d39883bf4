// strata-bench's coverage agreement: silhouettes excluded, real differences counted.
#include <gtest/gtest.h>

#include "Coverage.h"

using strata::bench::compareCoverage;

TEST(BenchCoverage, CountsInteriorDisagreementsAndSkipsEdges) {
    // 6 x 6: a 4 x 4 square in both; `b` also covers the corner pixel next to
    // the square's corner: a disagreement on a silhouette, not away from it.
    std::vector<std::uint8_t> a(36, 0), b(36, 0);
    for (int y = 1; y <= 4; ++y)
        for (int x = 1; x <= 4; ++x) a[y * 6 + x] = b[y * 6 + x] = 1;
    b[5 * 6 + 5] = 1;
    const auto agreement = compareCoverage(a, b, 6, 6);
    EXPECT_EQ(agreement.pixels, 36u);
    EXPECT_EQ(agreement.agreeing, 35u);
    EXPECT_EQ(agreement.coveredA, 16u);
    EXPECT_EQ(agreement.coveredB, 17u);
    EXPECT_EQ(agreement.interiorAgreeing, agreement.interiorPixels);
}

TEST(BenchCoverage, AWrongRegionCountsAwayFromEdges) {
    std::vector<std::uint8_t> a(100, 1), b(100, 1);
    for (int y = 3; y < 7; ++y)
        for (int x = 3; x < 7; ++x) b[y * 10 + x] = 0;  // a 4 x 4 hole only `b` has
    const auto agreement = compareCoverage(a, b, 10, 10);
    EXPECT_EQ(agreement.interiorPixels - agreement.interiorAgreeing, 4u);  // the hole's 2 x 2 core
    EXPECT_DOUBLE_EQ(agreement.interiorFraction(), 1.0 - 4.0 / double(agreement.interiorPixels));
    EXPECT_EQ(agreement.interiorCovered, agreement.interiorPixels);  // `a` covers everything

}
