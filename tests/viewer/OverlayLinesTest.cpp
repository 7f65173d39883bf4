// The lines strata-view draws over the image (apps/strata-view/OverlayLines.h):
// OpenSCAD's axes and scale markers (GLView::showAxes, showScalemarkers), its
// corner axis cross (GLView::showSmallaxes), and the edges of "show edges".

#include <gtest/gtest.h>

#include <cmath>

#include "OverlayLines.h"

using namespace strata;
using view::WorldSegment;

TEST(OverlayLines, TickSpacingIsATenthOfThePowerOfTenBelowTheDistance) {
    // OpenSCAD: pow(10, floor(log10(l))) / 10.
    EXPECT_DOUBLE_EQ(view::scaleTickSpacing(140.0), 10.0);
    EXPECT_DOUBLE_EQ(view::scaleTickSpacing(100.0), 10.0);
    EXPECT_DOUBLE_EQ(view::scaleTickSpacing(99.0), 1.0);
    EXPECT_DOUBLE_EQ(view::scaleTickSpacing(2.5), 0.1);
    EXPECT_DOUBLE_EQ(view::scaleTickSpacing(1500.0), 100.0);
}

TEST(OverlayLines, AxesRunTheDistanceEachWayWithTheNegativeHalfDashed) {
    const auto axes = view::axisSegments(50.0, false);
    ASSERT_EQ(axes.size(), 6u);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(axes[2 * axis].b[axis], 50.0);
        EXPECT_FALSE(axes[2 * axis].dashed);
        EXPECT_EQ(axes[2 * axis + 1].b[axis], -50.0);
        EXPECT_TRUE(axes[2 * axis + 1].dashed);
    }
}

TEST(OverlayLines, ScaleMarkersAsOpenScadDrawsThem) {
    // l = 140: ticks every 10 from 0 to 130, 14 of them on each half axis,
    // 140 / 60 long, the tenth (at 100) 140 / 30; X's towards -Y, Y's and Z's towards -X.
    const auto lines = view::axisSegments(140.0, true);
    ASSERT_EQ(lines.size(), 6u + 14u * 6u);
    int xTicks = 0;
    for (std::size_t k = 6; k < lines.size(); ++k) {
        const WorldSegment& s = lines[k];
        if (s.a.y != 0.0 || s.a.z != 0.0 || s.b.x != s.a.x || s.b.z != 0.0) continue;  // not an X tick
        if (s.a.x < 0.0 || (s.a.x == 0.0 && s.dashed)) continue;
        ++xTicks;
        EXPECT_NEAR(std::fmod(s.a.x, 10.0), 0.0, 1e-9);
        EXPECT_DOUBLE_EQ(s.b.y, s.a.x == 100.0 ? -140.0 / 30.0 : -140.0 / 60.0) << s.a.x;
    }
    EXPECT_EQ(xTicks, 14);
    const WorldSegment& zTick = lines[6 + 2];  // the first tick's Z one, at the origin
    EXPECT_EQ(zTick.b, glm::dvec3(-140.0 / 60.0, 0, 0));
}

TEST(OverlayLines, TheCornerCrossTurnsWithTheCamera) {
    render::Camera top;
    top.eye = {0, 0, 100};
    top.center = {0, 0, 0};
    top.width = 360;
    top.height = 180;
    const auto cross = view::gizmoSegments(top, glm::vec3(0));
    ASSERT_GE(cross.size(), 3u);
    // Origin a tenth in from the lower-left corner; each axis 10 of a 90 half-height: h / 18.
    const glm::dvec2 origin(36, 18);
    EXPECT_EQ(cross[0].a, origin);
    EXPECT_NEAR(cross[0].b.x, 36 + 10.0, 1e-9);  // X to the right
    EXPECT_NEAR(cross[0].b.y, 18, 1e-9);
    EXPECT_NEAR(cross[1].b.y, 18 + 10.0, 1e-9);  // Y up, seen from the top
    EXPECT_NEAR(glm::length(cross[2].b - origin), 0.0, 1e-9);  // Z towards the eye: a point
    EXPECT_EQ(cross[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(cross[2].color, glm::vec3(0, 0, 1));
}

TEST(OverlayLines, EdgesAreEachTrianglesEdgesOnce) {
    geometry::Mesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    std::vector<glm::vec3> points;
    view::appendMeshEdges(square, points);
    EXPECT_EQ(points.size(), 2u * 5u);  // four sides and the diagonal
}

TEST(OverlayLines, AxesColourIsTheSchemes) {
    EXPECT_EQ(view::axesColor("Cornfield"), glm::vec3(0));
    EXPECT_NEAR(view::axesColor("Tomorrow Night").r, 0xe8 / 255.0f, 1e-6);
}
