#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>

#include "strata/contour/Contour.h"

namespace strata::contour {

namespace {

// Two faces whose normals are within 20 degrees of opposite bound a slab;
// faces that meet at a wider angle bound a wedge, which is thin only near
// its edge, and that edge the contour rebuilds from the crossings around.
const float kFacingDot = -std::cos(20.0f * 3.14159265f / 180.0f);

}  // namespace

std::optional<FeatureBelowGrid> featureBelowGrid(const Dexels& dexels) {
    const DexelGrid& grid = dexels.grid;
    std::optional<FeatureBelowGrid> lost;
    // Of the walls and gaps crossed squarely that are thinner than a cell,
    // lost or not: a finer grid must see this one too.
    double thinnest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const DexelRays& rays = dexels.axes[static_cast<std::size_t>(a)];
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        const std::size_t rayCount = rays.first.empty() ? 0 : rays.first.size() - 1;
        for (std::size_t r = 0; r < rayCount; ++r) {
            for (std::uint32_t i = rays.first[r]; i + 1 < rays.first[r + 1]; ++i) {
                const Crossing& low = rays.crossings[i];
                const Crossing& high = rays.crossings[i + 1];
                const double thickness = high.at - low.at;
                if (!(thickness < grid.spacing)) continue;
                if (std::abs(low.normal[a]) <= 0.5f || std::abs(high.normal[a]) <= 0.5f) continue;
                if (glm::dot(low.normal, high.normal) >= kFacingDot) continue;
                thinnest = std::min(thinnest, thickness);
                if (lost) continue;
                // The signs count a crossing at or below a grid point as
                // before it: the span is seen where a grid point lies in
                // [low, high). The first grid point at or above low:
                int first = static_cast<int>(std::ceil((low.at - grid.origin[a]) / grid.spacing));
                while (gridCoordinate(grid, a, first - 1) >= low.at) --first;
                while (gridCoordinate(grid, a, first) < low.at) ++first;
                if (gridCoordinate(grid, a, first) < high.at) continue;
                glm::dvec3 middle;
                middle[a] = 0.5 * (low.at + high.at);
                middle[u] = gridCoordinate(grid, u, static_cast<int>(r % static_cast<std::size_t>(grid.count[u])));
                middle[v] = gridCoordinate(grid, v, static_cast<int>(r / static_cast<std::size_t>(grid.count[u])));
                lost = FeatureBelowGrid{low.entering, 0.0, middle};
            }
        }
    }
    if (lost) lost->thickness = thinnest;
    return lost;
}

}  // namespace strata::contour
