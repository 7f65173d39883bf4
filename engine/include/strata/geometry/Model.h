#pragma once
// A scene's leaves turned into world-space meshes, ready for the renderer and
// the reference. Knows the leaves, not the boolean operations between them.

#include <vector>

#include "strata/geometry/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::geometry {

struct Model {
    std::vector<Mesh> leafMeshes;  // leafMeshes[i] is tree.leaves[i] in world space; may be empty
    Bounds bounds;                 // of the non-background leaves
};

// Tessellates or imports each leaf, applies its transform, drops zero-area
// triangles and checks the result. A leaf that is not closed and consistently
// oriented throws strata::Error naming the leaf's file:line and what is wrong.
Model buildModel(const scene::Tree& tree);

}  // namespace strata::geometry
