#pragma once
// Per-triangle values carried by vertices: a re-indexing of a mesh in which
// no two triangles share their last corner. A flat-shaded attribute takes
// its value from one corner of each triangle (OpenGL's provoking vertex, the
// last by default), so with this layout that corner's attribute can hold a
// value of the triangle's own, its face normal, with no lookup by triangle
// id at every fragment.

#include <array>
#include <cstdint>
#include <vector>

#include "strata/mesh/Mesh.h"

namespace strata::mesh {

struct LastCornerLayout {
    // Per vertex of the layout, the mesh vertex it copies; the mesh's
    // vertices come first, in order, then the copies.
    std::vector<std::uint32_t> source;
    // The mesh's triangles, in order and with their corners in order (so a
    // rasterizer sets each up exactly as the mesh's own), re-indexed so that
    // a triangle's last corner is the last corner of no other.
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// A vertex is copied for every triangle past the first that ends on it. A
// closed mesh has about twice as many triangles as vertices, and a regular
// one ends two triangles on each vertex, so about one vertex in two is copied.
LastCornerLayout lastCornerLayout(const Mesh& mesh);

}  // namespace strata::mesh
