#pragma once
// A scene's leaves turned into world-space meshes, ready for the renderer and
// the reference. Knows the leaves, not the boolean operations between them.

#include <vector>

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::model {

struct Model {
    std::vector<mesh::Mesh> leafMeshes;  // leafMeshes[i] is tree.leaves[i] in world space; may be empty
    mesh::Bounds bounds;                 // of the non-background leaves
    std::vector<Warning> warnings;       // what was forgiven: inside-out or degenerate user meshes
};

// Tessellates or imports each leaf, applies its transform (and the
// resize() groups it is in), drops zero-area triangles and checks the
// result. A polyhedron or imported mesh that is closed but wound inside out
// is turned outward, and its degenerate triangles dropped, each with a
// warning in Model::warnings (OpenSCAD renders such meshes). A leaf that is not closed and consistently
// oriented throws strata::Error naming the leaf's file:line and what is wrong,
// e.g. "a.csg:7:5: polyhedron is not a closed solid: not closed: 3 boundary
// edges"; import and tessellation errors are prefixed with the leaf's position
// too. A leaf whose transform is singular (a scale of 0) gets an empty mesh; a
// non-finite coordinate throws. Bounds cover the leaves reachable from
// tree.root that are not Display::Background; empty when there are none.
Model buildModel(const scene::Tree& tree);

// One leaf's solid in world space: tessellated, imported or evaluated, then
// transformed; not yet cleaned or checked (buildModel does that).
mesh::Mesh leafMesh(const scene::Leaf& leaf);

// A primitive's solid in its own object space: leafMesh before the transform.
mesh::Mesh objectMesh(const scene::Primitive& primitive);

}  // namespace strata::model
