#pragma once
// Flat subtrees evaluated as OpenSCAD 2021.01's GeometryEvaluator does, node by
// node: primitives made as its primitives.cc makes them, booleans, offsets and
// every union of several children through Clipper on the 1/65536 grid, a
// single child passed through untouched, multmatrix applied to the points.

#include "strata/flat/Outlines.h"
#include "strata/scene/Flat.h"
#include "strata/scene/Tree.h"

namespace strata::model {

// The outlines of the tree's root (empty when it makes nothing). Errors from
// text, imports or coordinates beyond Clipper's range throw strata::Error
// naming the node's position.
flat::Outlines evaluateFlat(const scene::FlatTree& tree);

// The 2D result of a flat model (scene::Tree::isFlat): its slab leaves'
// shapes, each under its transform, combined by the tree's unions,
// differences and intersections as OpenSCAD combines 2D children, cleaned
// by Clipper (no crossings, outer outlines counter-clockwise). What a 2D
// export writes.
flat::Outlines flatResult(const scene::Tree& tree);

// The outlines of one flat primitive, before any union (square and circle come
// out as made, unsanitized shapes go through Clipper's even-odd clean-up).
flat::Outlines flatPrimitive(const scene::FlatPrimitive& primitive);

}  // namespace strata::model
