#include "strata/mesh/Mesh.h"

#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace strata::mesh {

void Bounds::extend(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

void Bounds::extend(const Bounds& b) {
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
}

double Bounds::diagonal() const {
    return empty() ? 0.0 : glm::length(max - min);
}

Bounds boundsOf(const Mesh& mesh) {
    Bounds b;
    for (const auto& p : mesh.positions) b.extend(p);
    return b;
}

Mesh transformed(const Mesh& mesh, const glm::dmat4& transform) {
    Mesh out;
    out.positions.reserve(mesh.positions.size());
    // The bottom row is ignored, as OpenSCAD's affine Transform3d does.
    for (const auto& p : mesh.positions) out.positions.emplace_back(glm::dvec3(transform * glm::dvec4(p, 1.0)));
    out.triangles = mesh.triangles;
    if (glm::determinant(glm::dmat3(transform)) < 0.0) {
        for (auto& t : out.triangles) std::swap(t[1], t[2]);
    }
    return out;
}

}  // namespace strata::mesh
