#pragma once
// What a frame does, decided on the CPU from the scene, the view and the
// settings before any pass runs: which of the scene's compiled trees the
// evaluator walks, whether the frame is drawn plainly (PlainPass.h),
// peeled and evaluated, or neither, and how its surfaces are lit. No GL:
// Renderer.cpp carries the plan out.

#include <array>
#include <cstddef>

#include "strata/csg/CompiledTree.h"
#include "strata/render/Frame.h"

namespace strata::render {

// The scene's tree compiled three ways (Renderer::setScene): every operand
// its own; convex intersections grouped (ConvexGroups.h); and those with
// the operands that only unions lead to grouped, for views where every ray
// starts outside.
enum class TreeForm { Separate, Grouped, UnionGrouped };

// What the renderer knows of the scene and the view when it plans a frame.
struct FrameFacts {
    bool outside = false;               // every ray starts outside the model (beyondNearPlane)
    bool plainScene = false;            // a union of leaves a plain frame can draw (PlainPass::plainLeaves)
    bool resultPeel = false;            // Renderer::sampleResult's frame: it walks past the first surface
    bool aovs = false;                  // the depth, normal and leaf images will be read back
    std::size_t unionOnlyOperands = 0;  // the operands groupUnionOperands may join
    std::array<csg::CompiledTree::Kind, 3> kinds{};  // each TreeForm's kind: an empty result, everything, or code
};

struct FramePlan {
    TreeForm form = TreeForm::Separate;  // the tree the evaluator walks
    bool plainFrame = false;             // drawn plainly: no peel or evaluator
    bool shownOnly = false;              // a plain frame nothing reads back
    bool evaluated = false;              // peeled and evaluated
    bool aovNormals = false;             // its normals are read back
    bool litAsDrawn = false;             // lit as its surfaces are drawn: no shade pass
};

FramePlan planFrame(const FrameFacts& facts, const RenderSettings& settings);

}  // namespace strata::render
