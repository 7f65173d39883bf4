// The debug views' images (apps/strata-view/DebugImage.h), on a hand-made frame.

#include <gtest/gtest.h>

#include <cmath>

#include "DebugImage.h"

using namespace strata;

TEST(DebugImage, DepthIsBrightNearDarkFarBlackOnMiss) {
    render::Frame frame;
    frame.width = 3;
    frame.height = 1;
    frame.depth = {1.0f, 3.0f, INFINITY};
    frame.normal = {glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0), glm::vec3(0)};
    const view::DebugImage depth = view::depthImage(frame);
    EXPECT_EQ(depth.rgba[0], 255);
    EXPECT_EQ(depth.rgba[4], 40);
    EXPECT_EQ(depth.rgba[8], 0);
    const view::DebugImage normal = view::normalImage(frame);
    EXPECT_EQ((std::vector<std::uint8_t>(normal.rgba.begin(), normal.rgba.begin() + 8)),
              (std::vector<std::uint8_t>{128, 128, 255, 255, 0, 128, 128, 255}));
    EXPECT_EQ(normal.rgba[8], 0);
}

TEST(DebugImage, PeelGridHasABlockPerOperandAndNearFarPerLayer) {
    render::Frame frame;
    frame.width = 8;
    frame.height = 4;
    const std::vector<float> full(32, 2.0f);
    frame.peelLayers = {{0, 0, full, full}, {0, 1, full, full}, {3, 0, full, full}};
    const view::PeelGrid grid = view::peelGrid(frame, 200, 100);
    ASSERT_EQ(grid.tiles.size(), 6u);
    EXPECT_EQ(grid.image.rgba.size(), 200u * 100u * 4u);
    const view::PeelTile& last = grid.tiles.back();
    EXPECT_EQ(last.leaf, 3);
    EXPECT_TRUE(last.far);
    EXPECT_TRUE(last.y > grid.tiles[0].y || last.x > grid.tiles[3].x);  // the second operand's block comes after
    EXPECT_EQ(grid.tiles[3].x, grid.tiles[2].x + grid.tiles[2].w + 2);  // layer 1's far beside its near
    // A tile is drawn: its first pixel is the grey of the (single) depth, not the background.
    const std::size_t p = (static_cast<std::size_t>(last.y) * 200 + last.x) * 4;
    EXPECT_EQ(grid.image.rgba[p], 255);
}

TEST(DebugImage, FormsTintTheShadedImageByBlockForm) {
    render::Frame frame;
    frame.width = 3;
    frame.height = 1;
    frame.rgba = {200, 100, 50, 255, 200, 100, 50, 255, 90, 90, 90, 255};
    frame.blockForms = {render::BlockForm::None, render::BlockForm::FirstSurface, render::BlockForm::Array};
    const view::DebugImage forms = view::formsImage(frame);
    ASSERT_EQ(forms.rgba.size(), 12u);
    EXPECT_EQ((std::vector<std::uint8_t>(forms.rgba.begin(), forms.rgba.begin() + 4)),
              (std::vector<std::uint8_t>{66, 33, 16, 255}));  // not drawn: dimmed to a third
    EXPECT_EQ((std::vector<std::uint8_t>(forms.rgba.begin() + 4, forms.rgba.begin() + 8)),
              (std::vector<std::uint8_t>{100, 129, 82, 255}));  // halfway to the first-surface green
    EXPECT_EQ((std::vector<std::uint8_t>(forms.rgba.begin() + 8, forms.rgba.end())),
              (std::vector<std::uint8_t>{147, 105, 128, 255}));  // halfway to the array form's pink
}
