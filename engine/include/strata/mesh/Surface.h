#pragma once
// surface(): a height map as a closed solid, meshed as OpenSCAD 2021.01 does.

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::mesh {

// Reads the .dat text or PNG image and builds the solid: 4 triangles per cell
// fanning to the cell's centre, the base at min(0, lowest - 1). Throws
// strata::Error (no position: the caller adds the node's) on unreadable or
// malformed input.
Mesh tessellate(const scene::Surface& surface);

}  // namespace strata::mesh
