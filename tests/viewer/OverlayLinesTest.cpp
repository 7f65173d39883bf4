// The lines strata-view draws over the image (apps/strata-view/OverlayLines.h):
// OpenSCAD's axes and scale markers (GLView::showAxes, showScalemarkers), its
// corner axis cross (GLView::showSmallaxes), and the edges of "show edges".

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

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
    camera::Camera top;
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
    mesh::Mesh square;
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

namespace {

// The texts on the positive X half axis, nearest first.
std::vector<std::string> positiveXTexts(double distance) {
    std::vector<std::string> texts;
    for (const view::ScaleLabel& label : view::scaleLabels(distance))
        if (label.axis == 0 && label.at > 0.0) texts.push_back(label.text);
    return texts;
}

// The bounding box of the segments, as {min, max}.
std::pair<glm::dvec3, glm::dvec3> bounds(const std::vector<WorldSegment>& segments) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const WorldSegment& s : segments) {
        lo = glm::min(lo, glm::min(s.a, s.b));
        hi = glm::max(hi, glm::max(s.a, s.b));
    }
    return {lo, hi};
}

}  // namespace

TEST(OverlayLines, ScaleNumbersStandAtTheMajorTicksAndEverySecondTickWhenFewMajorsShow) {
    // l = 500: ticks every 10 up to 490, majors at 100..400; 500 / 100 = 5 is
    // not under 3, so the majors only.
    EXPECT_EQ(positiveXTexts(500.0), (std::vector<std::string>{"100", "200", "300", "400"}));
    // l = 140: 140 / 100 < 3: every second tick as well, 20 to 120.
    EXPECT_EQ(positiveXTexts(140.0), (std::vector<std::string>{"20", "40", "60", "80", "100", "120"}));
    // l = 2.45: ticks every 0.1 up to 2.4, every second one labelled, as %g writes it.
    EXPECT_EQ(positiveXTexts(2.45), (std::vector<std::string>{"0.2", "0.4", "0.6", "0.8", "1", "1.2", "1.4",
                                                             "1.6", "1.8", "2", "2.2", "2.4"}));
    // l = 0.000045: ticks every 0.000001, majors at 0.00001..0.00004.
    EXPECT_EQ(positiveXTexts(0.000045), (std::vector<std::string>{"1e-05", "2e-05", "3e-05", "4e-05"}));
    // Every half axis gets the same numbers, the negative ones with a minus sign.
    const auto labels = view::scaleLabels(500.0);
    ASSERT_EQ(labels.size(), 4u * 6u);
    int negativeZ = 0;
    for (const view::ScaleLabel& label : labels)
        if (label.axis == 2 && label.at < 0.0) {
            ++negativeZ;
            EXPECT_EQ(label.text, "-" + std::to_string(static_cast<int>(-label.at))) << label.at;
        }
    EXPECT_EQ(negativeZ, 4);
}

TEST(OverlayLines, ScaleNumbersAreLaidOutBesideTheirTick) {
    // l = 60: u = 1, labels 10, 20, 30, 40, 50 and their negatives on each axis.
    // Each character is 0.5 wide on a pitch of 0.75, 0.25 to 1.25 from the axis.
    const auto all = view::scaleLabelSegments(60.0);
    auto near = [&](const glm::dvec3& p) {
        std::vector<WorldSegment> out;
        for (const WorldSegment& s : all)
            if (glm::length(s.a - p) < 2.0 && glm::length(s.b - p) < 2.0) out.push_back(s);
        return out;
    };
    // "10" on +X: '1' centred on x = 10, '0' on 10.75; in z = 0 on the +Y side.
    auto [lo, hi] = bounds(near({10.4, 0.75, 0.0}));
    EXPECT_NEAR(lo.x, 10.25, 1e-12);  // '1' is its cell's right side only
    EXPECT_NEAR(hi.x, 10.75 + 0.25, 1e-12);
    EXPECT_NEAR(lo.y, 0.25, 1e-12);
    EXPECT_NEAR(hi.y, 1.25, 1e-12);
    EXPECT_EQ(lo.z, 0.0);
    EXPECT_EQ(hi.z, 0.0);
    // The '1' alone: the upright at x = 10.25 from y = 0.25 to 1.25.
    int ones = 0;
    for (const WorldSegment& s : all)
        ones += s.a.x == 10.25 && s.b.x == 10.25 && std::min(s.a.y, s.b.y) == 0.25 && std::max(s.a.y, s.b.y) == 1.25;
    EXPECT_EQ(ones, 1);
    // "10" on +Y reads along -Y: '0' centred on y = 10, '1' on 10.75, whose
    // upright is its right side, y = 10.5; on the +X side.
    std::tie(lo, hi) = bounds(near({0.75, 10.4, 0.0}));
    EXPECT_NEAR(lo.y, 9.75, 1e-12);
    EXPECT_NEAR(hi.y, 10.5, 1e-12);  // past the '0' only the '1''s upright
    EXPECT_NEAR(lo.x, 0.25, 1e-12);
    EXPECT_NEAR(hi.x, 1.25, 1e-12);
    int yOnes = 0;
    for (const WorldSegment& s : all)
        yOnes += s.a.y == 10.5 && s.b.y == 10.5 && s.a.x != s.b.x && s.a.z == 0.0 && s.b.z == 0.0;
    EXPECT_EQ(yOnes, 1);
    // "-10" on -X reads along +X, so laid from the tick outwards "0", "1", "-":
    // the minus sign's bar at x = -11.5 +- 0.25, 7/8 from the axis.
    int minus = 0;
    for (const WorldSegment& s : all)
        minus += s.a.y == 0.875 && s.b.y == 0.875 && std::min(s.a.x, s.b.x) == -11.75 &&
                 std::max(s.a.x, s.b.x) == -11.25 && s.a.z == 0.0;
    EXPECT_EQ(minus, 1);
    // "50" on +Z: in the XZ plane (y = 0), on the +X side, '0' centred on z = 50.
    std::tie(lo, hi) = bounds(near({0.75, 0.0, 50.4}));
    EXPECT_EQ(lo.y, 0.0);
    EXPECT_EQ(hi.y, 0.0);
    EXPECT_NEAR(lo.z, 49.75, 1e-12);
    EXPECT_NEAR(lo.x, 0.25, 1e-12);
    EXPECT_NEAR(hi.x, 1.25, 1e-12);
}
