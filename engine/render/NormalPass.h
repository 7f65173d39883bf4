#pragma once
// The normal pass: recovers the world-space outward normal of the evaluated
// result. Every operand the result shows in a tile is drawn once more, only
// the faces it shows there (front, back or both, as the evaluator recorded:
// EvaluatePass::shownFaces; the others are culled before rasterizing), clipped
// to its screen rectangle, over the pixels the evaluator wrote (stencil test on
// FrameTargets::marks, so no other fragment runs the shader); the fragment
// whose leaf, facing and tagged depth match the evaluator's choice writes its
// triangle's face normal (a flat attribute of its last vertex: SceneBuffers.h),
// negated where the leaf acts as a subtracted operand, and in w the surface's
// base colour for the shade pass (ShadePass::baseColors). One more geometry pass
// instead of storing ids with every peeled layer, and nothing read back.
//
// With leaf marks (FrameTargets::mark) the stencil test lets through only the
// pixels that show the drawn leaf with the fragment's facing and the draw's
// flip (a leaf is drawn once per flip it shows). Where no other operand
// with the leaf's mark slot meets its rectangle (always, up to 63
// operands: FrameTargets::assignMarkSlots), a convex leaf's fragments
// that pass are the evaluator's surfaces, so they skip the comparisons
// (normal.frag's TRUST_MARKS).
//
// A group of convex operands (ConvexGroups.h) is one operand to the
// evaluator, which writes, marks and reports shown the member that makes
// each of its surfaces (the group's peel kept it: GroupPeel.h); here its
// members are leaves like any other.
//
// Lit (a frame without the outline, RenderSettings::outline): the fragment
// writes its lit colour into FrameTargets::color instead of the normal
// (normal.frag's LIT), as the shade pass would have lit it; the frame then
// needs no shade pass, only the image cleared to the background first.
//
// GL state: uses the scissor and stencil tests and turns them off before
// returning, and face culling; expects blending and depth test off.

#include <array>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/csg/CompiledTree.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/render/ColorScheme.h"

namespace strata::render {

class NormalPass {
public:
    NormalPass();

    // `tree.operandLeaf[k]` is operand k's tree leaf and `rects[k]` its screen
    // rectangle; `shownFaces[leaf]` says which faces of the leaf the result
    // shows in the tile (EvaluatePass::shownFaces): only those are drawn.
    // `baseColors[leaf]` is the leaf's ShadePass::baseColors entry.
    // A group operand's members (csg::CompiledTree::leavesOf) are each drawn as a
    // leaf of their own within the group's rectangle. `markLeaves` and
    // `markRects`: the leaves that hold mark slots this frame and their
    // screen rectangles, as FrameTargets::assignMarkSlots got them.
    // `litAs`: light the surfaces in that light into the image instead.
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
             const csg::CompiledTree& tree, const std::vector<PixelRect>& rects,
             const std::vector<std::uint32_t>& shownFaces, const std::vector<glm::vec2>& baseColors,
             std::span<const int> markLeaves, std::span<const PixelRect> markRects,
             const std::optional<Lighting>& litAs);

private:
    // The variant for a leaf: `trusted` (TRUST_MARKS: the stencil test has
    // compared leaf, facing and depth with the evaluator's) or the checking
    // one, writing normals or lit (`litAs`); made at its first use.
    gpu::Program& program(bool trusted, const std::optional<Lighting>& litAs);
    // [unlit, strata's light, OpenSCAD's][checking, trusting]
    std::array<std::array<std::optional<gpu::Program>, 2>, 3> programs_;
};

}  // namespace strata::render
