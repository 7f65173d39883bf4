#pragma once
// minkowski() of solids that are not all convex, as OpenSCAD 2021.01 computes
// it: each operand split into convex parts (CGAL's convex decomposition where
// it is not convex), the hull of every choice of one part per operand moved
// by each other's corners, and the union of those hulls, exactly.

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::model {

// The closed, outward sum, relative to the sum's leaf (its transform places
// it). An operand with no solid is left out, as OpenSCAD leaves it out; the
// sum is empty when every operand is.
// Results share the exact results' cache (by the operands' meshes). Throws
// strata::Error when an operand's mesh cannot be split, or when the sum
// would take more than 4096 hulls.
mesh::Mesh minkowskiSum(const scene::MinkowskiSum& sum);

}  // namespace strata::model
