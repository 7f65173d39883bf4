#include "FramePlan.h"

#include <algorithm>

namespace strata::render {

FramePlan planFrame(const FrameFacts& facts, const RenderSettings& settings) {
    FramePlan plan;
    // A union of leaves seen from outside is drawn plainly (PlainPass.h),
    // except where a frame asks for what only the peel has: the layers, the
    // evaluator's forms, or the result's later surfaces.
    plan.plainFrame = settings.plainUnions && facts.outside && facts.plainScene && !facts.resultPeel &&
                      !settings.keepPeelLayers && !settings.keepBlockForms;
    // Debug views show each operand's own layers: no groups there. Unions
    // group where every ray starts outside, as the first layer does
    // (Renderer's peelAndEvaluate), and not for the result peel, which
    // walks past it.
    const bool unions = facts.outside && !facts.resultPeel &&
                        facts.unionOnlyOperands >= static_cast<std::size_t>(std::max(settings.unionGroupFrom, 2));
    plan.form = !settings.groupOperands || settings.keepPeelLayers ? TreeForm::Separate
                : unions                                            ? TreeForm::UnionGrouped
                                                                    : TreeForm::Grouped;
    // A plain frame only shown (nothing read back) writes what the image
    // and the passes after it need and nothing else, and clears that itself
    // (PlainPass::Output::shownOnly).
    plan.shownOnly = plan.plainFrame && !facts.aovs;
    plan.evaluated = !plan.plainFrame &&
                     facts.kinds[static_cast<std::size_t>(plan.form)] == csg::CompiledTree::Kind::Code;
    // A frame with no outline is lit as its surfaces are drawn: no shade
    // pass, whose outline alone needs the G-buffer around a pixel. A plain
    // frame by the plain pass (PlainPass.h), an evaluated one by the normal
    // pass (NormalPass.h), where its normals are not read back.
    plan.aovNormals = facts.aovs && settings.readNormal;
    plan.litAsDrawn =
        !settings.outline && (plan.plainFrame || (plan.evaluated && !plan.aovNormals && !facts.resultPeel));
    return plan;
}

}  // namespace strata::render
