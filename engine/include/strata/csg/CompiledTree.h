#pragma once
// The CSG tree compiled into postfix code over boolean operands (a
// CompiledTree). The renderer specialises the code to each block of pixels
// (specializeCode) and hands the evaluator each specialised tree in the
// form it walks (countingTree, or a truth table: engine/render/EvaluatePass);
// runCode runs the code on the CPU, for tests. All of it is CPU work with no
// GL: the words of docs/architecture.md's glossary (operand, leaf, literal)
// are used as defined there.
//
// Compilation:
//   1. Difference(A, B, C) becomes A ∩ ¬B ∩ ¬C, and complements are pushed down
//      to the leaves (De Morgan), so only n-ary AND/OR over literals remain.
//   2. Constants fold: an empty leaf (no triangles, or a '%' background leaf)
//      is the empty set; Union() and Intersection() are empty, and so is a
//      Difference with an empty first child; A ∩ ∅ = ∅, A ∪ ∅ = A, ¬∅ = everything.
//      Nested ANDs (ORs) flatten, single-child nodes vanish. A literal that an
//      AND (OR) holds is true (false) wherever its other children matter, so
//      below them it is a constant and folds too (with identical leaves
//      sharing a leaf, `sameLeaf`, a solid intersected at every level of a
//      chain is left at the outermost level only).
//   3. Children are ordered Sethi–Ullman style (AND and OR commute): the child
//      that needs the deepest stack goes first, and leaf children are fused into
//      AND_LIT/OR_LIT instructions that push nothing. A tree of L leaves then
//      needs at most floor(log2 L) + 1 stack entries, so runCode's whole
//      stack is one 32-bit word for any tree the machine can hold.
//
// Instruction word (uint32):
//   bits 0-1  operation (kOpMask): 0 PUSH, 1 AND, 2 OR
//   bit  2    source: 0 literal (operand state, bits 4..31), 1 pop the stack
//   bit  3    negate the literal
//   bits 4-31 operand index (literals only)
// PUSH always takes a literal. AND/OR combine the stack top with the source.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "strata/scene/Tree.h"

namespace strata::csg {

inline constexpr std::uint32_t kOpPush = 0u;
inline constexpr std::uint32_t kOpAnd = 1u;
inline constexpr std::uint32_t kOpOr = 2u;
inline constexpr std::uint32_t kOpMask = 3u;  // the operation's bits
inline constexpr std::uint32_t kOpFromStack = 4u;
inline constexpr std::uint32_t kOpNegate = 8u;
inline constexpr int kOperandShift = 4;
inline constexpr int kMaxStackDepth = 32;  // bits in runCode's stack word

struct CompiledTree {
    // What the root folded to: code to run, or a constant.
    enum class Kind { Code, Empty, Everything };
    Kind kind = Kind::Empty;

    std::vector<std::uint32_t> code;  // the instructions, see above
    std::vector<int> operandLeaf;     // operand index -> tree leaf index, ascending
    // Per operand, where groupConvexProducts (ConvexGroups.h) made it the
    // intersection of several convex leaves: those leaves, ascending (the
    // first is operandLeaf's). Empty for every other operand, and when no
    // operand is a group.
    std::vector<std::vector<int>> operandGroups;
    // Per operand, where groupUnionOperands made it a group: 1, the group is
    // the union of its members rather than their intersection. Empty when no
    // group is a union.
    std::vector<char> unionGroups;
    int stackDepth = 0;               // deepest stack the code reaches

    int operandCount() const { return static_cast<int>(operandLeaf.size()); }
    // The tree leaves operand k stands for: a group's members, else its own leaf.
    std::span<const int> leavesOf(std::size_t k) const {
        if (k < operandGroups.size() && !operandGroups[k].empty()) return operandGroups[k];
        return {&operandLeaf[k], 1};
    }
    bool isUnionGroup(std::size_t k) const { return k < unionGroups.size() && unionGroups[k] != 0; }
};

// Compiles `tree` from tree.root. `leafIsEmpty[i]` marks leaf i as the empty set
// (e.g. a mesh with no triangles); an empty vector means no leaf is empty.
// `sameLeaf[i]` (IdenticalLeaves.h; empty: every leaf is its own) is a leaf
// with exactly leaf i's solid, whose operand leaf i's literals then use: the
// operands are the leaves that some leaf maps to.
// Leaves with Display::Background are always empty. Never recurses, so any
// tree depth compiles. Throws strata::Error on a malformed tree (a child index
// out of range, a cycle) or, for >2^31 leaves, a stack deeper than 32.
CompiledTree compileTree(const scene::Tree& tree, const std::vector<bool>& leafIsEmpty = {},
                         const std::vector<int>& sameLeaf = {});

// `compiled`'s code specialised to a part of the screen where only the operands with
// present[k] != 0 have surfaces: every other operand is outside there, so its
// literals become constants and fold away (A ∩ ¬B is A where B is absent; A ∩ B
// is empty). Operand indices are kept. Returns the instructions, or an empty
// vector when the result there is constant (empty or everything: no surface
// of the result in that part either way); `constant` tells which.
std::vector<std::uint32_t> specializeCode(const CompiledTree& compiled, const std::vector<char>& present,
                                          bool* constant = nullptr);

// Runs instructions symbolically, for the compilers that turn code into
// another form: `literal(instruction)` makes the stack entry of an
// instruction's literal, `combine(op, top, source)` folds `source` into the
// stack's `top` entry (op: kOpAnd or kOpOr), in place. Returns the one entry
// left. Non-empty, well-formed code only.
template <class Entry, class Literal, class Combine>
Entry foldCode(const std::vector<std::uint32_t>& code, Literal literal, Combine combine) {
    std::vector<Entry> stack;
    for (std::uint32_t instruction : code) {
        const std::uint32_t op = instruction & kOpMask;
        if (op == kOpPush) {
            stack.push_back(literal(instruction));
            continue;
        }
        Entry source;
        if (instruction & kOpFromStack) {
            source = std::move(stack.back());
            stack.pop_back();
        } else {
            source = literal(instruction);
        }
        combine(op, stack.back(), std::move(source));
    }
    return std::move(stack.back());
}

// Instructions (a compiled tree's or specialised ones) as a tree of counting
// nodes, the form the evaluator's array form walks: each inner node is an n-ary AND or OR
// that keeps how many of its children are true, so one operand's change
// updates only the nodes whose value it changes, up to the root.
struct CountingTree {
    struct Literal {
        std::uint32_t operand = 0;
        std::uint32_t parent = 0;  // index into nodes
        bool negated = false;
    };
    struct Node {
        std::uint32_t parent = kNoParent;  // index into nodes; kNoParent for the root
        bool isAnd = false;
        std::uint32_t children = 0;        // literals and nodes under it
        std::uint32_t trueWhenOutside = 0; // children true when every operand is outside
    };
    static constexpr std::uint32_t kNoParent = 0xffffffffu;
    std::vector<Literal> literals;  // in code order
    std::vector<Node> nodes;        // nodes[0] is the root; a parent comes before its children
};

// Non-empty `code` (as compileTree or specializeCode give it) as a counting
// tree. Code of one literal gets a one-child OR root, so there is always
// a root node. Nested nodes of the same operation merge.
CountingTree countingTree(const std::vector<std::uint32_t>& code);

// The counting tree's result for the given operand states, computed from the
// counts as the evaluator keeps them (for tests).
bool runCountingTree(const CountingTree& tree, const std::vector<bool>& operandInside);

// Runs instructions on a stack of bits (an empty sequence gives false), the
// meaning every other form of the tree must agree with (for tests).
// `operandInside[k]` is operand k's membership.
bool runCode(const std::vector<std::uint32_t>& code, const std::vector<bool>& operandInside);

// runCode on `compiled`, or its constant. `operandInside[k]` is operand k's
// membership. Returns the result's membership.
bool runCompiledTree(const CompiledTree& compiled, const std::vector<bool>& operandInside);

// One instruction per line ("PUSH !3", "AND pop", ...), for tests and debugging.
std::string disassemble(const CompiledTree& compiled);

}  // namespace strata::csg
