#pragma once
// Contouring of a tri-dexel image (Dexels.h) into a closed triangle mesh.

#include "strata/contour/Dexels.h"
#include "strata/geometry/Mesh.h"

namespace strata::contour {

// The boundary of the sampled solid: closed, 2-manifold, every triangle
// counter-clockwise seen from outside, no degenerate triangles. Sharp edges
// and corners of the solid are kept where a cell's crossings show them.
// Reports progress (core/Progress.h) per slab of cells. Throws strata::Error
// on an inconsistent image (a ray that ends inside, crossings out of order).
geometry::Mesh contour(const Dexels& dexels);

}  // namespace strata::contour
