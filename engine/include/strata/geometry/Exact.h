#pragma once
// The exact result of a CSG subtree as one closed mesh, through CGAL's
// corefinement with exact constructions (Polygon_mesh_processing, the
// Epeck kernel): for the nodes that need a result's geometry rather than an
// image of it (hull, resize, projection of a difference or intersection).
// Points come back rounded to doubles once.

#include <vector>

#include "strata/geometry/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::geometry {

// The result of tree.nodes[node] from the leaves' checked world-space meshes
// (Model::leafMeshes of the same tree). Throws strata::Error naming the node
// when CGAL cannot take a mesh (one that touches itself, or intersects itself).
Mesh exactResult(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes);

}  // namespace strata::geometry
