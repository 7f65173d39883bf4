// contour::featureBelowGrid on solids sampled in closed form: slabs and gaps
// thinner than a cell that no grid point sees are found, at any turn, with
// the thickness along the grid line; curved surfaces grazed by a line and the
// tip of a wedge are not slabs; a grid fine enough finds nothing.

#include <gtest/gtest.h>

#include <cmath>

#include "AnalyticDexels.h"
#include "strata/contour/Contour.h"

using namespace strata::contour;
using namespace strata::contour::test;

namespace {

const double kPi = 3.14159265358979323846;

}  // namespace

TEST(FeatureBelowGrid, AThinSlabAtAnyTurnIsAWallLost) {
    // 6 x 6 x 0.2, turned about x by 0, 20 and 40 degrees: along z it is
    // 0.2 / cos(angle) thick, the thinnest crossing of a grid line.
    for (double degrees : {0.0, 20.0, 40.0}) {
        SCOPED_TRACE(degrees);
        const double angle = degrees * kPi / 180.0;
        const SolidPtr slab = orientedBox(glm::dvec3(0.0), rotation(angle, 0.0, 0.0), glm::dvec3(3.0, 3.0, 0.1));
        const std::optional<FeatureBelowGrid> lost = featureBelowGrid(sample(*slab, gridAround(glm::dvec3(-4.0), glm::dvec3(4.0), 0.5)));
        ASSERT_TRUE(lost.has_value());
        EXPECT_TRUE(lost->wall);
        EXPECT_NEAR(lost->thickness, 0.2 / std::cos(angle), 1e-9);
        EXPECT_LT(std::abs(lost->where.x), 3.0);
        // A grid whose cell is two thirds of that sees it on every line.
        EXPECT_FALSE(featureBelowGrid(sample(*slab, gridAround(glm::dvec3(-4.0), glm::dvec3(4.0), 0.2 * 2.0 / 3.0))));
    }
}

TEST(FeatureBelowGrid, ANarrowGapIsAGapFilled) {
    const SolidPtr pair = unite({box(glm::dvec3(0.0), glm::dvec3(3.0)), box(glm::dvec3(3.15, 0.0, 0.0), glm::dvec3(6.0, 3.0, 3.0))});
    const std::optional<FeatureBelowGrid> lost = featureBelowGrid(sample(*pair, gridAround(glm::dvec3(0.0), glm::dvec3(6.0, 3.0, 3.0), 0.5)));
    ASSERT_TRUE(lost.has_value());
    EXPECT_FALSE(lost->wall);
    EXPECT_NEAR(lost->thickness, 0.15, 1e-9);
    EXPECT_NEAR(lost->where.x, 3.075, 1e-9);
}

TEST(FeatureBelowGrid, GrazedCurvesAndWedgeTipsAreNotSlabs) {
    // Lines that clip a ball's rim cross it in slivers far thinner than a cell.
    const SolidPtr ball = sphere(glm::dvec3(0.0), 3.0);
    EXPECT_FALSE(featureBelowGrid(sample(*ball, gridAround(glm::dvec3(-3.0), glm::dvec3(3.0), 0.5))));
    // A block less a block turned 30 degrees about z: a wedge whose faces
    // meet at 30 degrees, thinner than a cell near its edge.
    const SolidPtr wedge = subtract(box(glm::dvec3(0.0), glm::dvec3(4.0)),
                                    orientedBox(glm::dvec3(0.0, 4.0, 2.0), rotation(0.0, 0.0, 30.0 * kPi / 180.0), glm::dvec3(10.0, 4.0, 3.0)));
    const Dexels image = sample(*wedge, gridAround(glm::dvec3(0.0), glm::dvec3(4.0), 0.5));
    EXPECT_FALSE(featureBelowGrid(image));
}
