#pragma once
// Small helpers shared by the mesh, flat, exact and model tests, computed
// independently of the code under test (plain loops over triangles).

#include <cmath>

#include <glm/geometric.hpp>

#include "strata/mesh/Mesh.h"

namespace strata::mesh::test {

// Signed volume by the divergence theorem: positive for an outward closed mesh.
inline double signedVolume(const Mesh& m) {
    double v6 = 0.0;
    for (const auto& t : m.triangles) {
        v6 += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]]));
    }
    return v6 / 6.0;
}

inline double surfaceArea(const Mesh& m) {
    double a = 0.0;
    for (const auto& t : m.triangles) {
        a += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
    }
    return a;
}

inline glm::dvec3 triangleNormal(const Mesh& m, std::size_t i) {
    const auto& t = m.triangles[i];
    return glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

// Area of a regular n-gon with circumradius r.
inline double regularPolygonArea(int n, double r) {
    const double pi = 3.14159265358979323846;
    return 0.5 * n * r * r * std::sin(2.0 * pi / n);
}

}  // namespace strata::mesh::test
