#pragma once
// Per-ray CSG on interval lists: the reference's evaluator. It shares no code
// with the GPU evaluator (shaders/csg/), on purpose: it is what that one is
// checked against.
//
// Along one ray, each leaf is a list of intervals of the ray parameter t where
// the ray is inside the leaf; the tree combines the lists with union,
// intersection and difference; the first boundary of the result after the ray
// start is the visible surface (docs/architecture.md, "Visible surface semantics"):
//
//   leaf A   |=========|          |=====|
//   leaf B        |=========|
//   A - B    |====|               |=====|      first change: A's entry
//   A & B         |====|                       first change: B's entry
//   B - A              |====|                  first change: A's exit (normal flipped)
//
// Membership is defined on the open spans between boundaries, so touching
// intervals of a union merge ([a,b] u [b,c] = [a,c], no surface at b) and
// zero-length pieces of an intersection or difference vanish. Every list is
// kept canonical: sorted, begin < end, and a gap of positive length between
// neighbours; then each boundary is a real change of membership.

#include <optional>
#include <span>
#include <vector>

#include "strata/scene/Tree.h"

namespace strata::reference {

// Where a boundary comes from.
struct Surface {
    int leaf = -1;            // tree leaf index; -1: no surface (the ray start, or never)
    int crossing = -1;        // the caller's handle of the crossing (for its normal); -1: none
    bool leafEnters = false;  // the leaf's own membership goes from outside to inside here
};

struct Interval {
    double begin = 0.0;  // -infinity: inside from the ray start
    double end = 0.0;    // +infinity: never left
    Surface beginSurface;
    Surface endSurface;
};

using IntervalList = std::vector<Interval>;

// One crossing of a leaf's surface by the ray, after the ray start.
struct Crossing {
    double t = 0.0;         // ray parameter
    bool entering = false;  // the triangle faces the ray (dot(outward normal, direction) < 0)
    int handle = -1;        // the caller's handle, copied into Surface::crossing
};

// The leaf's interval list from all of its crossings after the ray start, in
// any order (reordered in place). Membership follows parity (docs/architecture.md,
// "Visible surface semantics"): the ray starts inside when the number of crossings is odd, and
// each crossing toggles it. Crossings whose t lie within `mergeTolerance` of
// the first of a group count as one point: a group of even size (a graze, or
// a shared edge that rounding made two hits of a fold) changes nothing, an odd
// one toggles, represented by its first crossing whose facing agrees with the
// change.
IntervalList leafIntervals(int leaf, std::span<Crossing> crossings, double mergeTolerance);
void leafIntervals(int leaf, std::span<Crossing> crossings, double mergeTolerance, IntervalList& out);

// Canonical in, canonical out. When two boundaries coincide, the surface of
// the first operand is kept.
void unite(const IntervalList& a, const IntervalList& b, IntervalList& out);
void intersect(const IntervalList& a, const IntervalList& b, IntervalList& out);
void subtract(const IntervalList& a, const IntervalList& b, IntervalList& out);
IntervalList unite(const IntervalList& a, const IntervalList& b);
IntervalList intersect(const IntervalList& a, const IntervalList& b);
IntervalList subtract(const IntervalList& a, const IntervalList& b);

// The first change of membership of a canonical list after the ray start.
struct FirstChange {
    double t = 0.0;
    Surface surface;
    bool resultEnters = true;  // false: the ray started inside and this is the first exit
    // The leaf acts as a subtracted operand here: its outward normal, negated,
    // is the result's outward normal.
    bool flipNormal() const { return surface.leafEnters != resultEnters; }
};
std::optional<FirstChange> firstChange(const IntervalList& list);

// The tree from nodes[root], compiled once into postfix order for evaluation
// ray after ray. Background leaves ('%') are not in the CSG: they count as
// empty. An empty union, an intersection with an empty child and a difference
// with an empty first child are empty. Throws strata::Error on a malformed
// tree (index out of range, a cycle).
class CsgProgram {
public:
    explicit CsgProgram(const scene::Tree& tree);

    // Leaves that take part in the result, ascending, without repeats.
    const std::vector<int>& leaves() const { return leaves_; }
    std::size_t leafCount() const { return leafCount_; }

    // Scratch space for evaluate(); one per thread.
    struct Workspace {
        std::vector<IntervalList> stack;
        IntervalList scratch;
    };

    // The result's interval list. leafLists[i] is tree.leaves[i]'s list
    // (size leafCount()); lists of leaves not in leaves() are not read.
    const IntervalList& evaluate(std::span<const IntervalList> leafLists, Workspace& workspace) const;

    // Membership at one point: inside[i] says whether tree.leaves[i] holds
    // it (size leafCount()). `stack` is scratch space.
    bool contains(std::span<const char> inside, std::vector<char>& stack) const;

private:
    enum class Op { Leaf, Empty, Union, Intersection, Difference };
    struct Instruction {
        Op op = Op::Empty;
        int operand = 0;  // Op::Leaf: the leaf; otherwise the number of children (>= 2)
    };
    std::vector<Instruction> code_;
    std::vector<int> leaves_;
    std::size_t leafCount_ = 0;
    std::size_t maxStack_ = 0;
};

}  // namespace strata::reference
