// The frame plan (engine/render/FramePlan.h) against the rules
// docs/algorithm.md states for each kind of frame: when a union is drawn
// plainly, which compiled tree the evaluator walks, and when the surfaces
// are lit as they are drawn. CPU only: the plan is made before any pass.

#include <gtest/gtest.h>

#include "FramePlan.h"

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
