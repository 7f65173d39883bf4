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
// intersection, A - (B & C), is A & (!B | !C) once compiled. An AND (OR)
// with fewer than `leastMembers` such literals keeps them apart. A group's
// operand is its lowest member leaf; operandGroups[group] of the result
// lists its member leaves, ascending. Operands are renumbered so that
// operandLeaf stays ascending.
CompiledTree groupConvexProducts(const CompiledTree& compiled, const std::vector<char>& groupable,
                                 std::size_t mostMembers, std::size_t leastMembers = 2);

// Unions of operands, peeled as one operand where only their nearest
// surface matters.
//
// Where only unions lead from the result to an operand and every ray starts
// outside every operand, the result is entered wherever the operand is, so
// the first layer of the operand (its nearest entry and farthest exit) is
// all the result can show of it (Renderer.cpp, reachedByUnionsOnly). The
// same holds for the union of several such operands: from the nearest of
// their entries to the farthest of their exits. So, in every OR of the
// counting tree, the plain literals of the operands with groupable[k] != 0
// that are each their operand's only literal and not a group already are
// joined as groupConvexProducts joins an intersection's, in runs of at most
// `mostMembers`, and the result marks them in unionGroups. A union of a
// million cubes becomes sixteen operands of one layer each. The caller
// guarantees the condition above: on a ray that starts inside a member, or
// where surfaces past the first matter (the result peel), the group's one
// interval is not the union.
CompiledTree groupUnionOperands(const CompiledTree& compiled, const std::vector<char>& groupable,
                                std::size_t mostMembers);

}  // namespace strata::csg
