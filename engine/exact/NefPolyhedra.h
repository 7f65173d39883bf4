#pragma once
// What strata does with CGAL's Nef polyhedra (the exact representation
// OpenSCAD 2021.01 evaluates with): a closed solid split into convex parts,
// for Minkowski sums (exact::convexParts); and a boolean of two solids where corefinement, the
// faster way, fails on a degenerate configuration; a result's coplanar
// triangles joined where the faster way refuses. Kept in one file, as Nef
// polyhedra are heavy to compile.

#include <vector>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <glm/vec3.hpp>

#include "strata/core/Error.h"
#include "strata/mesh/Mesh.h"

namespace strata::exact::detail {

// Whether a closed, outward, edge-manifold mesh bounds a convex solid, as
// OpenSCAD judges it: one connected surface with no reflex edge, where faces
// that meet at less than 0.1 degrees count as flat (a sphere's quads are flat
// only up to rounding). A mesh with an edge shared by more than two triangles
// is not convex.
bool isConvex(const mesh::Mesh& closed);

// Closed solids with exact points, as the exact evaluation keeps them.
using ExactSolid = CGAL::Surface_mesh<CGAL::Epeck::Point_3>;
enum class Boolean { Union, Intersection, Difference };

// A closed mesh with its points made exact. Throws strata::Error naming
// `where`, "<who> cannot take this solid: it touches itself ...", where a
// halfedge structure cannot hold it.
ExactSolid toExactSolid(const mesh::Mesh& mesh, const SourceLocation& where, const char* who);
// The same from exact points already made (`points[i]` is the mesh's
// vertex i) and the mesh's triangles.
ExactSolid toExactSolid(const std::vector<CGAL::Epeck::Point_3>& points, const mesh::Mesh& mesh, const SourceLocation& where,
                        const char* who);

// The same solid with each run of coplanar triangles joined into one face
// and retriangulated, and the points no edge needs gone, through a Nef
// polyhedron: what joinedCoplanarFaces (CoplanarFaces.h) does far faster,
// for the solids it refuses. Throws strata::Error naming `where` when CGAL
// cannot take the solid.
ExactSolid simplified(const ExactSolid& solid, const SourceLocation& where);

// a OP b through Nef polyhedra, triangulated. Throws strata::Error naming
// `where` when CGAL cannot take a solid.
ExactSolid nefBoolean(const ExactSolid& a, const ExactSolid& b, Boolean op, const SourceLocation& where);

}  // namespace strata::exact::detail
