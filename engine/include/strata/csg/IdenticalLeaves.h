#pragma once
// Leaves that are the same solid: the same triangles at the same world
// positions, bit for bit, with the same colour and display. Such leaves need
// peeling once, and the evaluator reads one operand's layers for all of them
// (compileTree's `sameLeaf`): a model that repeats one solid in several
// places of its tree (the same bounding sphere intersected at every level,
// say) then costs one operand, not one per repetition.
//
// The image, depth and normals stay as they were: identical leaves have
// their surfaces at the same depths with the same normals and colours. Only
// the leaf image may change, where it named one of several identical
// leaves: it now names the lowest of them, the one they all map to.

#include <vector>

#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::csg {

// Per tree leaf i: the lowest leaf whose solid is leaf i's exactly (i itself
// where no lower one is). Leaves without triangles map to themselves.
std::vector<int> identicalLeaves(const scene::Tree& tree, const model::Model& model);

}  // namespace strata::csg
