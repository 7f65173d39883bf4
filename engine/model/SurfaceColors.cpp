#include "strata/model/SurfaceColors.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace strata::model {

using mesh::Bounds;
using mesh::Mesh;
using mesh::boundsOf;

namespace {

// A leaf's triangle with what the centroid test needs.
struct Face {
    glm::dvec3 a, b, c, normal;  // normal of unit length
    glm::dvec3 lo, hi;           // box, padded
    int leaf;
};

bool holds(const Face& f, const glm::dvec3& p, double tolerance) {
    if (p.x < f.lo.x || p.y < f.lo.y || p.z < f.lo.z || p.x > f.hi.x || p.y > f.hi.y || p.z > f.hi.z) return false;
    if (std::fabs(glm::dot(p - f.a, f.normal)) > tolerance) return false;
    // Inside the triangle, seen along its normal (edges count as inside).
    const double eps = -tolerance;
    return glm::dot(glm::cross(f.b - f.a, p - f.a), f.normal) >= eps * glm::length(f.b - f.a) &&
           glm::dot(glm::cross(f.c - f.b, p - f.b), f.normal) >= eps * glm::length(f.c - f.b) &&
           glm::dot(glm::cross(f.a - f.c, p - f.c), f.normal) >= eps * glm::length(f.a - f.c);
}

}  // namespace

std::vector<glm::vec4> surfaceColors(const Mesh& result, const scene::Tree& tree, const Model& model,
                                     const glm::vec4& fallback, double reach) {
    const std::vector<int> leaves = tree.leavesUnder(tree.root);
    const bool anyColor = std::any_of(leaves.begin(), leaves.end(), [&](int l) {
        return tree.leaves[static_cast<std::size_t>(l)].color.has_value();
    });
    if (!anyColor) return {};
    Bounds box = boundsOf(result);
    const double tolerance = std::max(reach, 1e-9 * std::max(1.0, glm::length(box.max - box.min)));
    std::vector<Face> faces;
    for (int l : leaves) {
        const Mesh& m = model.leafMeshes[static_cast<std::size_t>(l)];
        for (const auto& t : m.triangles) {
            Face f{m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], {}, {}, {}, l};
            const glm::dvec3 n = glm::cross(f.b - f.a, f.c - f.a);
            const double length = glm::length(n);
            if (!(length > 0.0)) continue;
            f.normal = n / length;
            f.lo = glm::min(f.a, glm::min(f.b, f.c)) - tolerance;
            f.hi = glm::max(f.a, glm::max(f.b, f.c)) + tolerance;
            faces.push_back(f);
        }
    }
    // A grid over the result's box: each face listed in the cells its box
    // meets, each centroid tested against its own cell's faces.
    const int n = std::clamp(static_cast<int>(std::cbrt(static_cast<double>(faces.size()))), 1, 64);
    const glm::dvec3 lo = box.min - tolerance, size = (box.max - box.min) + 2.0 * tolerance;
    auto cellOf = [&](const glm::dvec3& p) {
        glm::ivec3 c;
        for (int k = 0; k < 3; ++k) {
            const double u = size[k] > 0.0 ? (p[k] - lo[k]) / size[k] : 0.0;
            c[k] = std::clamp(static_cast<int>(u * n), 0, n - 1);
        }
        return c;
    };
    std::vector<std::vector<int>> cells(static_cast<std::size_t>(n) * n * n);
    auto index = [n](const glm::ivec3& c) { return (static_cast<std::size_t>(c.z) * n + c.y) * n + c.x; };
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const glm::ivec3 a = cellOf(faces[f].lo), b = cellOf(faces[f].hi);
        for (int z = a.z; z <= b.z; ++z)
            for (int y = a.y; y <= b.y; ++y)
                for (int x = a.x; x <= b.x; ++x) cells[index({x, y, z})].push_back(static_cast<int>(f));
    }
    std::vector<glm::vec4> colors;
    colors.reserve(result.triangles.size());
    for (const auto& t : result.triangles) {
        const glm::dvec3 centroid = (result.positions[t[0]] + result.positions[t[1]] + result.positions[t[2]]) / 3.0;
        int leaf = -1;
        double nearest = 0.0;
        for (int f : cells[index(cellOf(centroid))]) {
            const Face& face = faces[static_cast<std::size_t>(f)];
            if (!holds(face, centroid, tolerance)) continue;
            const double distance = reach > 0.0 ? std::fabs(glm::dot(centroid - face.a, face.normal)) : 0.0;
            if (leaf < 0 || distance < nearest || (distance == nearest && face.leaf < leaf)) {
                leaf = face.leaf;
                nearest = distance;
            }
        }
        const std::optional<glm::dvec4>& c = leaf >= 0 ? tree.leaves[static_cast<std::size_t>(leaf)].color : std::nullopt;
        colors.push_back(c ? glm::vec4(*c) : fallback);
    }
    return colors;
}

}  // namespace strata::model
