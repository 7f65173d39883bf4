#pragma once
// Ear clipping of one planar (or nearly planar) polygon given by indices into a
// vertex array. Used for polyhedron faces and for the n-gons of imported files.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace strata::mesh::detail {

// Appends to `out` triangles covering the polygon `loop` (indices into
// `positions`), keeping its winding: a counter-clockwise loop (seen from where
// its Newell normal points) gives counter-clockwise triangles. Works in the
// plane of the Newell normal, so non-convex faces come out right. Consecutive
// repeated vertices are skipped; a loop of fewer than three distinct vertices
// gives nothing. Collinear vertices are kept out of ears where possible, so no
// zero-area triangle (and no T-junction) appears unless the polygon itself is
// degenerate.
void triangulatePolygon(const std::vector<glm::dvec3>& positions, std::span<const uint32_t> loop,
                        std::vector<std::array<uint32_t, 3>>& out);

}  // namespace strata::mesh::detail
