#pragma once
// A tri-dexel image as the contouring reads it: every ray checked once, then
// the grid's vertex signs one z plane at a time and the crossing of any grid
// edge. The rules for both are written here and nowhere else, so the signs a
// cell sees and the crossings its edges get always agree.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "Qef.h"
#include "strata/contour/Dexels.h"

namespace strata::contour {

class DexelImage {
public:
    // Throws strata::Error where the image breaks Dexels.h's rules: a ray with
    // an odd number of crossings, crossings out of order, an `entering` flag
    // that disagrees with the parity before it, rays missing.
    explicit DexelImage(const Dexels& dexels);

    // No cells, or no crossing on any ray: nothing to contour.
    bool empty() const { return empty_; }
    const DexelGrid& grid() const { return dexels_.grid; }

    // World coordinate of grid index `index` along `axis` (gridCoordinate).
    double coordinate(int axis, int index) const { return gridCoordinate(dexels_.grid, axis, index); }

    // Whether each grid vertex of plane z = k is inside: inside[i + j * count.x].
    // Call with k = 0, 1, 2, ... in order (the z rays keep a cursor each).
    void signPlane(int k, std::vector<std::uint8_t>& inside);

    // The Hermite sample of the grid edge from `vertex` to vertex + axis,
    // whose low end is inside or not (and the high end the opposite).
    HermiteSample edgeCrossing(const glm::ivec3& vertex, int axis, bool lowInside) const;

private:
    const Crossing* rayBegin(int axis, std::size_t ray) const;
    const Crossing* rayEnd(int axis, std::size_t ray) const;
    std::size_t rayIndex(int axis, int u, int v) const;
    void checkRays(int axis);
    void addParities(int axis, std::size_t ray, int along, int stride, std::vector<std::uint8_t>& votes) const;

    const Dexels& dexels_;
    bool empty_ = true;
    std::vector<std::uint32_t> zCursor_;  // per z ray: crossings at or below the last plane
    int nextPlane_ = 0;
};

}  // namespace strata::contour
