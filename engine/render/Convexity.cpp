#include "Convexity.h"

#include <cmath>
#include <variant>

#include <glm/geometric.hpp>

namespace strata::render {

bool isConvexLeaf(const scene::Primitive& primitive, const geometry::Mesh& mesh, double maxWork) {
    if (std::holds_alternative<scene::Cube>(primitive) || std::holds_alternative<scene::Sphere>(primitive) ||
        std::holds_alternative<scene::Cylinder>(primitive)) {
        return true;
    }
    const double work = static_cast<double>(mesh.positions.size()) * static_cast<double>(mesh.triangles.size());
    if (mesh.triangles.empty() || work > maxWork) return false;
    const double tolerance = 1e-9 * geometry::boundsOf(mesh).diagonal();
    for (const auto& t : mesh.triangles) {
        const glm::dvec3& a = mesh.positions[t[0]];
        const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);
        const double length = glm::length(n);
        if (length == 0.0) continue;
        const glm::dvec3 unit = n / length;
        for (const glm::dvec3& p : mesh.positions) {
            if (glm::dot(p - a, unit) > tolerance) return false;
        }
    }
    return true;
}

}  // namespace strata::render
