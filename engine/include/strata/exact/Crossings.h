#pragma once
// Where a mesh passes through itself: pairs of triangles that meet other
// than along the edge or at the corner they share, decided with exact
// predicates on the mesh's points (CGAL's filtered kernel). What a slicer
// calls a self-intersection; the sampled export looks for it in the mesh it
// is about to write, and the export benchmark's audit counts it.

#include <array>
#include <cstdint>
#include <vector>

#include "strata/mesh/Mesh.h"

namespace strata::exact {

// Every pair of triangles of `mesh` (indices into mesh.triangles, the lower
// first) that meet beyond what they share: with no corner in common, any
// contact; with one, the far edge of either touching the other; with an
// edge, both lying in one plane on one side of it (folded onto each
// other); the same three corners twice. Corners are shared by index, so
// points repeated at one position should be merged first (as a reader of
// the file welds them). Triangles without area (a repeated corner, or
// three on one line) are left out. In no particular order.
std::vector<std::array<std::uint32_t, 2>> crossingTriangles(const mesh::Mesh& mesh);

}  // namespace strata::exact
