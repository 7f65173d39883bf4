#include "Convexity.h"

#include <cmath>
#include <numeric>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

namespace strata::render {

bool isConvexLeaf(const scene::Primitive& primitive, const mesh::Mesh& mesh, double maxWork) {
    if (std::holds_alternative<scene::Cube>(primitive) || std::holds_alternative<scene::Sphere>(primitive) ||
        std::holds_alternative<scene::Cylinder>(primitive) || std::holds_alternative<scene::Hull>(primitive)) {
        return true;
    }
    const double work = static_cast<double>(mesh.positions.size()) * static_cast<double>(mesh.triangles.size());
    if (mesh.triangles.empty() || work > maxWork) return false;
    const double tolerance = 1e-9 * mesh::boundsOf(mesh).diagonal();
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

bool everyShellHasVolume(const mesh::Mesh& mesh) {
    // Shells: the vertices joined by triangles (union-find).
    std::vector<std::uint32_t> parent(mesh.positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : mesh.triangles) {
        parent[find(t[1])] = find(t[0]);
        parent[find(t[2])] = find(t[0]);
    }
    // Each shell's signed volume, by the divergence theorem.
    std::vector<double> volume(mesh.positions.size(), 0.0);
    std::vector<char> used(mesh.positions.size(), 0);
    for (const auto& t : mesh.triangles) {
        const std::uint32_t shell = find(t[0]);
        volume[shell] += glm::dot(mesh.positions[t[0]], glm::cross(mesh.positions[t[1]], mesh.positions[t[2]])) / 6.0;
        used[shell] = 1;
    }
    const double size = mesh::boundsOf(mesh).diagonal();
    const double least = 1e-12 * size * size * size;
    for (std::size_t v = 0; v < volume.size(); ++v) {
        if (used[v] && std::abs(volume[v]) <= least) return false;
    }
    return true;
}

}  // namespace strata::render
