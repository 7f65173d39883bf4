#pragma once
// A solid sampled along three axes (a tri-dexel image): the input of the
// contouring that turns the CSG result back into a mesh (Contour.h).
//
// The grid: vertices origin + spacing * (i, j, k), 0 <= i < count.x, and so
// on. The rays of axis a run along a (+a) through the grid vertices of the
// other two axes u = (a + 1) % 3, v = (a + 2) % 3: ray r = iu + iv * count[u]
// passes through origin[u] + spacing * iu, origin[v] + spacing * iv. Each ray
// lists every place where it crosses the solid's boundary, in increasing
// order along a, starting and ending outside: the grid's box holds the solid
// with room to spare, so the grid's outer vertices are all outside.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace strata::contour {

struct Crossing {
    double at = 0.0;         // world coordinate along the ray's axis
    glm::vec3 normal{0.0f};  // the solid's outward unit normal there
    bool entering = false;   // the ray (going +axis) enters the solid here
};

struct DexelGrid {
    glm::dvec3 origin{0.0};  // grid vertex (0, 0, 0), world space
    double spacing = 1.0;    // the cells' edge length
    glm::ivec3 count{0};     // grid vertices along x, y, z (cells: count - 1)
};

// World coordinate of grid index `index` along `axis`. Every comparison of
// a crossing with a grid vertex goes through this one expression: a
// crossing at or below it counts as before the vertex.
inline double gridCoordinate(const DexelGrid& grid, int axis, int index) {
    return grid.origin[axis] + grid.spacing * index;
}

// One axis's rays, packed: ray r's crossings are
// crossings[first[r]] .. crossings[first[r + 1] - 1].
struct DexelRays {
    std::vector<std::uint32_t> first;  // rays + 1 entries
    std::vector<Crossing> crossings;
};

struct Dexels {
    DexelGrid grid;
    std::array<DexelRays, 3> axes;  // rays along x, y, z
};

}  // namespace strata::contour
