#pragma once
// Intersections of convex operands, peeled as one operand.
//
// On any ray a convex solid is one interval (or nothing), and so is the
// intersection of several: it runs from the farthest of their entries to
// the nearest of their exits, where every one of them is hit. The peel pass
// peels all of them into one layer (GroupPeel.h), keeping which member
// makes each surface (on a tie, the lowest leaf, as the CPU reference keeps
// the first operand's surface), and the evaluator then reads one operand
// where it read one per solid: the intersection of 256 spheres becomes one
// layer and a one-literal tree. Where it writes a group's surface, it
// writes that member's leaf, so the later passes see the members as leaves.
// Images are unchanged by grouping (tests compare both ways).

#include <cstddef>
#include <vector>

#include "strata/csg/CompiledTree.h"

namespace strata::csg {

// `compiled` with, in every AND of its counting tree (CompiledTree.h), the
// plain literals of the operands with groupable[k] != 0 that are each their
// operand's only literal in the code, joined into one operand per run of at
// most `mostMembers`: the run's first literal in code order stands for all
// of them (it now names the group's operand) and the others leave the code.
// So do the negated ones in every OR: !a | !b is !(a & b), and a subtracted
// intersection, A - (B & C), is A & (!B | !C) once compiled. A group's
// operand is its lowest member leaf; operandGroups[group] of the result
// lists its member leaves, ascending. Operands are renumbered so that
// operandLeaf stays ascending.
CompiledTree groupConvexProducts(const CompiledTree& compiled, const std::vector<char>& groupable,
                                 std::size_t mostMembers);

}  // namespace strata::csg
