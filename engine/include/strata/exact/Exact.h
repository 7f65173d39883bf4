#pragma once
// The exact result of a CSG subtree as one closed mesh, through CGAL's
// corefinement with exact constructions (Polygon_mesh_processing, the
// Epeck kernel): for the nodes that need a result's geometry rather than an
// image of it (hull, resize, projection of a difference or intersection).
// Points come back rounded to doubles once. Also the convex parts of a
// solid, through Nef polyhedra, for Minkowski sums.

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/core/Error.h"
#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::exact {

// A primitive's solid in its own object space, before its transform
// (model::objectMesh): how exactResult remakes a leaf's points exactly.
using ObjectMesh = std::function<mesh::Mesh(const scene::Primitive&)>;

// The result of tree.nodes[node] from the leaves' checked world-space meshes
// (Model::leafMeshes of the same tree); `objectMesh` remakes a leaf whose
// transform chain it can apply exactly. Throws strata::Error naming the node
// when CGAL cannot take a mesh (one that touches itself, or intersects itself).
// Results are kept by their content (the subtree's operations and its leaves'
// meshes, bit for bit), up to about 256 MiB in all, so a reload whose edit
// leaves the subtree alone does not evaluate it again. Thread-safe.
mesh::Mesh exactResult(const scene::Tree& tree, int node, const std::vector<mesh::Mesh>& leafMeshes, const ObjectMesh& objectMesh);

// The union of closed solids (the convex pieces of a minkowski sum), exactly;
// not cached (its callers cache what they make of it). Throws strata::Error
// naming `where` when CGAL cannot take a solid or the union is not a manifold.
mesh::Mesh exactUnion(std::vector<mesh::Mesh> solids, const SourceLocation& where);

// The corners of each convex part of `closed`: one part, its own corners,
// when it is convex. Throws strata::Error naming `where` when CGAL cannot
// take the mesh.
std::vector<std::vector<glm::dvec3>> convexParts(const mesh::Mesh& closed, const SourceLocation& where);

// How many results the cache has answered in this process (exactResult and
// minkowski sums).
std::size_t exactCacheHits();

}  // namespace strata::exact
