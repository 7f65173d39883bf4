#pragma once
// A closed solid as convex parts, for Minkowski sums: the solid itself when it
// is convex, else CGAL's convex decomposition of its Nef polyhedron (the
// decomposition OpenSCAD 2021.01 takes). Each part is given by its corners.

#include <vector>

#include <glm/vec3.hpp>

#include "strata/core/Error.h"
#include "strata/geometry/Mesh.h"

namespace strata::geometry::detail {

// Whether a closed, outward, edge-manifold mesh bounds a convex solid, as
// OpenSCAD judges it: one connected surface with no reflex edge, where faces
// that meet at less than 0.1 degrees count as flat (a sphere's quads are flat
// only up to rounding). A mesh with an edge shared by more than two triangles
// is not convex.
bool isConvex(const Mesh& closed);

// The corners of each convex part of `closed`: one part, its own corners,
// when it is convex. Throws strata::Error naming `where` when CGAL cannot
// take the mesh.
std::vector<std::vector<glm::dvec3>> convexParts(const Mesh& closed, const SourceLocation& where);

}  // namespace strata::geometry::detail
