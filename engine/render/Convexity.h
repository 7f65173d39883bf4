#pragma once
// Which leaves are convex: a convex operand has at most two surfaces on any
// ray, so one dual-peel pass captures it completely and `auto` peeling needs
// no occlusion query for it. And which leaves have a shell of no volume,
// whose entry and exit share one depth.

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::render {

// True when `mesh` (the leaf's world-space mesh) bounds a convex solid.
// Cubes, spheres and cylinders/cones are convex under any affine transform;
// polyhedra and imports are tested (every vertex on the inner side of every
// face plane) when that costs at most `maxWork` vertex-plane tests, and are
// assumed non-convex above it.
bool isConvexLeaf(const scene::Primitive& primitive, const mesh::Mesh& mesh,
                  double maxWork = 4.0e6);

// False when a connected shell of `mesh` encloses no volume (within 1e-12
// of its bounding box's diagonal cubed): a flat, double-sided part, which a
// ray enters and leaves at one depth. The renderer peels such a leaf in
// full even where one layer would otherwise do (Renderer.cpp), since the
// first layer alone would keep the entry and lose the exit.
bool everyShellHasVolume(const mesh::Mesh& mesh);

}  // namespace strata::render
