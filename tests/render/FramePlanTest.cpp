// The frame plan (engine/render/FramePlan.h) against the rules
// docs/algorithm.md states for each kind of frame: when a union is drawn
// plainly, which compiled tree the evaluator walks, when the surfaces are
// lit as they are drawn, and which tiles a frame is drawn in (every pixel
// in one tile, each within the memory budget, cut further for operands
// small on screen only while that saves layers). CPU only: the plan is
// made before any pass.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "FramePlan.h"
#include "strata/core/Error.h"

using namespace strata;
using render::FrameFacts;
using render::FramePlan;
using render::RenderSettings;
using render::TreeForm;
using Kind = csg::CompiledTree::Kind;

namespace {

// A union of leaves, seen from outside, shown in a window.
FrameFacts unionFromOutside() {
    FrameFacts facts;
    facts.outside = true;
    facts.plainScene = true;
    facts.unionOnlyOperands = 3;
    facts.kinds = {Kind::Code, Kind::Code, Kind::Code};
    return facts;
}

// A difference seen from outside, its image read back.
FrameFacts differenceReadBack() {
    FrameFacts facts;
    facts.outside = true;
    facts.aovs = true;
    facts.unionOnlyOperands = 1;
    facts.kinds = {Kind::Code, Kind::Code, Kind::Code};
    return facts;
}

RenderSettings openScadLook() {
    RenderSettings settings;
    settings.outline = false;
    settings.lighting = render::Lighting::OpenScad;
    return settings;
}

}  // namespace

TEST(FramePlan, AUnionSeenFromOutsideIsDrawnPlainlyAndOnlyShownInAWindow) {
    const FramePlan shown = render::planFrame(unionFromOutside(), RenderSettings{});
    EXPECT_TRUE(shown.plainFrame);
    EXPECT_FALSE(shown.evaluated);
    EXPECT_TRUE(shown.shownOnly);
    EXPECT_FALSE(shown.litAsDrawn);  // the outline needs the shade pass

    FrameFacts read = unionFromOutside();
    read.aovs = true;
    const FramePlan readBack = render::planFrame(read, openScadLook());
    EXPECT_TRUE(readBack.plainFrame);
    EXPECT_FALSE(readBack.shownOnly);
    EXPECT_TRUE(readBack.aovNormals);
    EXPECT_TRUE(readBack.litAsDrawn);  // a plain frame lights as it draws, normals read or not
}

TEST(FramePlan, WhatOnlyThePeelHasIsNeverDrawnPlainly) {
    auto plainWith = [](FrameFacts facts, RenderSettings settings) {
        return render::planFrame(facts, settings).plainFrame;
    };
    FrameFacts inside = unionFromOutside();
    inside.outside = false;
    EXPECT_FALSE(plainWith(inside, RenderSettings{}));
    FrameFacts resultPeel = unionFromOutside();
    resultPeel.resultPeel = true;
    EXPECT_FALSE(plainWith(resultPeel, RenderSettings{}));
    RenderSettings layers;
    layers.keepPeelLayers = true;
    EXPECT_FALSE(plainWith(unionFromOutside(), layers));
    RenderSettings forms;
    forms.keepBlockForms = true;
    EXPECT_FALSE(plainWith(unionFromOutside(), forms));
    RenderSettings off;
    off.plainUnions = false;
    EXPECT_FALSE(plainWith(unionFromOutside(), off));
    // Every one of them is peeled and evaluated instead.
    EXPECT_TRUE(render::planFrame(inside, RenderSettings{}).evaluated);
}

TEST(FramePlan, UnionOperandsAreGroupedOnlyWhereEveryRayStartsOutside) {
    RenderSettings settings;
    settings.unionGroupFrom = 2;
    FrameFacts facts = differenceReadBack();
    facts.unionOnlyOperands = 2;
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::UnionGrouped);
    facts.unionOnlyOperands = 1;  // nothing to join
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Grouped);
    facts.unionOnlyOperands = 2;
    facts.outside = false;
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Grouped);
    facts.outside = true;
    facts.resultPeel = true;  // it walks past the first surface
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Grouped);
    facts.resultPeel = false;
    settings.unionGroupFrom = 3;  // fewer operands than the setting asks
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Grouped);
    // Debug views and frames that ask for no groups see every operand.
    settings.unionGroupFrom = 2;
    settings.keepPeelLayers = true;
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Separate);
    settings.keepPeelLayers = false;
    settings.groupOperands = false;
    EXPECT_EQ(render::planFrame(facts, settings).form, TreeForm::Separate);
}

TEST(FramePlan, AnEvaluatedFrameIsLitAsDrawnOnlyWhereNoNormalIsReadBack) {
    EXPECT_FALSE(render::planFrame(differenceReadBack(), openScadLook()).litAsDrawn);
    RenderSettings noNormals = openScadLook();
    noNormals.readNormal = false;
    const FramePlan depthOnly = render::planFrame(differenceReadBack(), noNormals);
    EXPECT_TRUE(depthOnly.evaluated);
    EXPECT_FALSE(depthOnly.aovNormals);
    EXPECT_TRUE(depthOnly.litAsDrawn);
    FrameFacts window = differenceReadBack();
    window.aovs = false;
    EXPECT_TRUE(render::planFrame(window, openScadLook()).litAsDrawn);
    EXPECT_FALSE(render::planFrame(window, RenderSettings{}).litAsDrawn);  // strata's outline
    window.resultPeel = true;  // nothing is shaded there
    EXPECT_FALSE(render::planFrame(window, openScadLook()).litAsDrawn);
}

TEST(FramePlan, OnlyAViewFromOutsideOfAnImagePeelsUnionOperandsOneLayerDeep) {
    const FramePlan image = render::planFrame(differenceReadBack(), RenderSettings{});
    EXPECT_TRUE(image.firstLayerOnly);
    EXPECT_FALSE(image.resultPeel);
    FrameFacts inside = differenceReadBack();
    inside.outside = false;  // a ray starting inside an operand needs its later layers
    EXPECT_FALSE(render::planFrame(inside, RenderSettings{}).firstLayerOnly);
    RenderSettings layers;
    layers.keepPeelLayers = true;  // the debug views show every layer
    EXPECT_FALSE(render::planFrame(differenceReadBack(), layers).firstLayerOnly);
    FrameFacts result = differenceReadBack();
    result.resultPeel = true;  // the result peel walks past the first surface
    const FramePlan rounds = render::planFrame(result, RenderSettings{});
    EXPECT_TRUE(rounds.resultPeel);
    EXPECT_FALSE(rounds.firstLayerOnly);
    EXPECT_TRUE(rounds.evaluated);
}

TEST(FramePlan, AResultWithNoCodeIsNeitherDrawnNorEvaluated) {
    for (const Kind kind : {Kind::Empty, Kind::Everything}) {
        FrameFacts facts = differenceReadBack();
        facts.kinds = {kind, kind, kind};
        const FramePlan plan = render::planFrame(facts, RenderSettings{});
        EXPECT_FALSE(plan.plainFrame);
        EXPECT_FALSE(plan.evaluated);
        EXPECT_FALSE(plan.litAsDrawn);
    }
    // The kind read is the chosen form's.
    FrameFacts mixed = differenceReadBack();
    mixed.kinds = {Kind::Empty, Kind::Code, Kind::Empty};
    EXPECT_TRUE(render::planFrame(mixed, RenderSettings{}).evaluated);
    RenderSettings separate;
    separate.groupOperands = false;
    EXPECT_FALSE(render::planFrame(mixed, separate).evaluated);
}

namespace {

// Every pixel of a width x height frame in exactly one tile.
void expectPartition(const std::vector<render::PixelRect>& tiles, int width, int height) {
    std::vector<int> covered(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    for (const render::PixelRect& t : tiles) {
        ASSERT_FALSE(t.empty());
        for (int y = t.y; y < t.y + t.height; ++y)
            for (int x = t.x; x < t.x + t.width; ++x) {
                ASSERT_TRUE(x >= 0 && x < width && y >= 0 && y < height) << x << "," << y;
                ++covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
            }
    }
    for (int c : covered) ASSERT_EQ(c, 1);
}

// A tile's layers: `layers` for each operand it meets, 8 bytes a layer and pixel.
render::TileEstimate perOperand(const std::vector<char>& inTile, int layers) {
    int met = 0;
    for (char c : inTile) met += c ? 1 : 0;
    const int total = std::max(1, met * layers);
    return {total, static_cast<std::size_t>(total) * 8};
}

}  // namespace

TEST(TilePlan, QuartersCutOnTheBlockGridAndKeepEveryPixel) {
    const render::PixelRect tile{10, 20, 100, 40};
    const std::vector<render::PixelRect> parts = render::quarters(tile, 16);
    ASSERT_EQ(parts.size(), 4u);
    for (const render::PixelRect& p : parts) {
        EXPECT_EQ((p.x - tile.x) % 16, 0);  // cuts fall on the block grid from the tile's corner
        EXPECT_EQ((p.y - tile.y) % 16, 0);
    }
    std::vector<render::PixelRect> moved;
    for (render::PixelRect p : parts) moved.push_back({p.x - tile.x, p.y - tile.y, p.width, p.height});
    expectPartition(moved, tile.width, tile.height);
    // A side shorter than two blocks is kept whole; a tile with both cannot be cut.
    EXPECT_EQ(render::quarters({0, 0, 100, 20}, 16).size(), 2u);
    EXPECT_EQ(render::quarters({0, 0, 31, 31}, 16).size(), 1u);
}

TEST(TilePlan, AFrameWithinTheBudgetIsOneTileAndAFrameBeyondItIsCutUntilEachTileFits) {
    const std::vector<render::PixelRect> rects{{0, 0, 512, 512}};  // one operand over the whole frame
    auto threeLayers = [](const std::vector<char>& inTile) { return perOperand(inTile, 3); };
    RenderSettings settings;
    settings.memoryBudget = 512 * 512 * 24;
    settings.coverageTilingFrom = settings.memoryBudget;
    render::TileGrid one = render::planTileGrid(512, 512, rects, settings, 16, threeLayers);
    EXPECT_EQ(one.tiles.size(), 1u);
    EXPECT_EQ(one.budgetTiles, 1u);
    EXPECT_EQ(one.wholeLayerBytes, std::size_t(512) * 512 * 24);

    settings.memoryBudget = 512 * 512 * 24 / 4;  // a quarter of the frame's layers
    render::TileGrid four = render::planTileGrid(512, 512, rects, settings, 16, threeLayers);
    EXPECT_EQ(four.tiles.size(), 4u);
    EXPECT_EQ(four.budgetTiles, 4u);
    expectPartition(four.tiles, 512, 512);
    for (const render::PixelRect& t : four.tiles)
        EXPECT_LE(std::size_t(24) * static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height),
                  settings.memoryBudget);

    settings.memoryBudget = 16 * 16 * 24 - 1;  // not even one block's layers
    EXPECT_THROW(render::planTileGrid(512, 512, rects, settings, 16, threeLayers), strata::Error);
}

TEST(TilePlan, OperandsSmallOnScreenAreTiledByCoverageWhileItSavesLayers) {
    // Four small operands, one in each corner of the frame: a quarter meets
    // one of them, so its layers are a quarter of the frame's.
    const std::vector<render::PixelRect> corners{{0, 0, 40, 40}, {472, 0, 40, 40}, {0, 472, 40, 40}, {472, 472, 40, 40}};
    auto eightLayers = [](const std::vector<char>& inTile) { return perOperand(inTile, 8); };
    RenderSettings settings;
    settings.memoryBudget = std::size_t(1) << 30;  // the budget asks for no tiles
    settings.coverageTilingFrom = 1;
    const render::TileGrid grid = render::planTileGrid(512, 512, corners, settings, 16, eightLayers);
    EXPECT_EQ(grid.budgetTiles, 1u);
    EXPECT_GT(grid.tiles.size(), 1u);
    expectPartition(grid.tiles, 512, 512);
    for (const render::PixelRect& t : grid.tiles) EXPECT_GE(std::min(t.width, t.height), 64);  // never below 64 a side

    // An operand over the whole frame meets every quarter: cutting would
    // draw it four times for no fewer layers a tile, so the frame stays whole.
    const std::vector<render::PixelRect> whole{{0, 0, 512, 512}};
    EXPECT_EQ(render::planTileGrid(512, 512, whole, settings, 16, eightLayers).tiles.size(), 1u);
}

TEST(FramePlan, PlainLeavesBesideCsgAreDrawnPlainlyWhereTheyReachEnoughBlocksAlone) {
    FrameFacts facts = differenceReadBack();
    facts.plainBesideScene = true;
    facts.plainBesideShare = 0.5;
    const FramePlan beside = render::planFrame(facts, RenderSettings{});
    EXPECT_TRUE(beside.plainBeside);
    EXPECT_FALSE(beside.plainFrame);
    EXPECT_TRUE(beside.evaluated);
    EXPECT_EQ(beside.form, TreeForm::BesidePlainGrouped);
    RenderSettings apart;
    apart.groupOperands = false;
    EXPECT_EQ(render::planFrame(facts, apart).form, TreeForm::BesidePlainSeparate);
    // Not where the plain leaves reach few blocks alone, from inside, for
    // the result peel, the debug views, or with plain frames turned off.
    FrameFacts few = facts;
    few.plainBesideShare = RenderSettings{}.plainBesideFrom / 2;
    EXPECT_FALSE(render::planFrame(few, RenderSettings{}).plainBeside);
    FrameFacts inside = facts;
    inside.outside = false;
    EXPECT_FALSE(render::planFrame(inside, RenderSettings{}).plainBeside);
    FrameFacts peel = facts;
    peel.resultPeel = true;
    EXPECT_FALSE(render::planFrame(peel, RenderSettings{}).plainBeside);
    RenderSettings layers;
    layers.keepPeelLayers = true;
    EXPECT_FALSE(render::planFrame(facts, layers).plainBeside);
    RenderSettings forms;
    forms.keepBlockForms = true;
    EXPECT_FALSE(render::planFrame(facts, forms).plainBeside);
    RenderSettings off;
    off.plainUnions = false;
    EXPECT_FALSE(render::planFrame(facts, off).plainBeside);
    EXPECT_EQ(render::planFrame(facts, off).form, TreeForm::Grouped);
    // Lit as drawn without the outline, as any evaluated frame.
    facts.aovs = false;
    EXPECT_TRUE(render::planFrame(facts, openScadLook()).litAsDrawn);
}

TEST(FramePlan, PlainBesideShareCountsTheBlocksOnlyPlainLeavesReach) {
    using render::PixelRect;
    // A 64 x 32 frame of 16-pixel blocks (4 x 2): a plain leaf over the
    // left half, a CSG operand over the right half and one block column
    // of the left.
    const std::vector<PixelRect> plain{{0, 0, 32, 32}}, csg{{20, 0, 44, 32}};
    EXPECT_DOUBLE_EQ(render::plainBesideShare(64, 32, 16, plain, csg), 2.0 / 8.0);
    EXPECT_DOUBLE_EQ(render::plainBesideShare(64, 32, 16, plain, {}), 1.0);
    EXPECT_DOUBLE_EQ(render::plainBesideShare(64, 32, 16, {}, csg), 0.0);
    EXPECT_DOUBLE_EQ(render::plainBesideShare(64, 32, 16, {}, {}), 0.0);
    // Off the frame counts nothing; a rectangle past its edge is cut there.
    EXPECT_DOUBLE_EQ(render::plainBesideShare(64, 32, 16, {{-40, 0, 20, 32}, {60, 0, 40, 32}}, csg), 0.0);
}
