#include "strata/mesh/Mesh.h"

#include <algorithm>
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

void canonicalOrder(Mesh& mesh) {
    std::vector<uint32_t> byPosition(mesh.positions.size());
    for (std::size_t v = 0; v < byPosition.size(); ++v) byPosition[v] = static_cast<uint32_t>(v);
    std::stable_sort(byPosition.begin(), byPosition.end(), [&](uint32_t a, uint32_t b) {
        const glm::dvec3& p = mesh.positions[a];
        const glm::dvec3& q = mesh.positions[b];
        return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z < q.z;
    });
    std::vector<uint32_t> rank(byPosition.size());
    std::vector<glm::dvec3> positions(byPosition.size());
    for (std::size_t r = 0; r < byPosition.size(); ++r) {
        rank[byPosition[r]] = static_cast<uint32_t>(r);
        positions[r] = mesh.positions[byPosition[r]];
    }
    mesh.positions = std::move(positions);
    for (std::array<uint32_t, 3>& t : mesh.triangles) {
        for (uint32_t& v : t) v = rank[v];
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    }
    std::sort(mesh.triangles.begin(), mesh.triangles.end());
}

}  // namespace strata::mesh
