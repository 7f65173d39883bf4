#include "ViewMatrices.h"

#include <algorithm>

namespace strata::bench {

ViewMatrices fittedView(const camera::Camera& camera, const mesh::Bounds& bounds) {
    double nearest = 1e300, farthest = -1e300;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p{c & 1 ? bounds.max.x : bounds.min.x, c & 2 ? bounds.max.y : bounds.min.y,
                           c & 4 ? bounds.max.z : bounds.min.z};
        const double d = camera.viewDepth(p);
        nearest = std::min(nearest, d);
        farthest = std::max(farthest, d);
    }
    const double margin = 0.01 * std::max(bounds.diagonal(), 1e-6);
    const double zFar = std::max(farthest + margin, 2 * margin);
    const double zNear = std::max(nearest - margin, zFar * 1e-4);
    return {camera.viewMatrix(), camera.projectionMatrix(zNear, zFar)};
}

}  // namespace strata::bench
