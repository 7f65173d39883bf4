#pragma once
// The contour's flat regions rebuilt on the planes they lie on: where a
// patch vertex sits on its crossings' planes (Contour.cpp's snapping), the
// many small triangles of a flat face, or of a sharp edge between two,
// carry no more shape than the face's corners do, and are merged away.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "ContourStats.h"
#include "strata/contour/Planes.h"
#include "strata/mesh/Mesh.h"

namespace strata::contour {

// A contour vertex's planes (PlaneTable ids, in increasing order, -1 after
// the last): one inside a flat region, two on a sharp edge, three or more
// at a corner; none where its patch's crossings do not meet in one point.
inline constexpr int kMostPlanes = 6;
using VertexPlanes = std::array<std::int32_t, kMostPlanes>;
inline constexpr VertexPlanes kNoPlanes{-1, -1, -1, -1, -1, -1};

// Removes every vertex it can by collapsing it into a neighbour such that
// the surface, as a set of points, stays the same: each triangle around the
// removed vertex lies on a plane that the neighbour lies on too, and every
// triangle the collapse makes keeps its facing within that plane with room
// to spare (no sliver below kMinMergedShape). A collapse that would join
// two sheets (the neighbours' rings share more than the edge's two
// opposite vertices) is refused, so a closed 2-manifold stays one. A
// triangle lies on a plane when all three of its vertices do and it faces
// the plane's way. Counts removed vertices in `stats`.
mesh::Mesh mergeFlatRegions(const mesh::Mesh& mesh, const std::vector<VertexPlanes>& vertexPlanes,
                            const PlaneTable& planes, ContourStats& stats);

// Twice a merged triangle's area over its longest edge squared, at least.
inline constexpr double kMinMergedShape = 1e-4;

// The square of the longest edge of triangle a, b, c: what a triangle's
// shape (twice its area over it) is measured against, here and in the
// contour's choice of diagonals.
inline double longestEdgeSquared(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, bc = c - b, ca = a - c;
    return std::max({glm::dot(ab, ab), glm::dot(bc, bc), glm::dot(ca, ca)});
}

}  // namespace strata::contour
