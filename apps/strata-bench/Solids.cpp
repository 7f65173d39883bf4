#include "Solids.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace strata::bench {
namespace {

// A closed tube: ring i (of `segments`, wrapping) holds `rings` points
// (wrapping), point (i, j) at index i * rings + j. The caller places the
// points so that increasing i then j turns counter-clockwise seen from
// outside; the faces are written clockwise, as OpenSCAD's polyhedron wants.
void addTubeFaces(scene::Polyhedron& out, int segments, int rings) {
    auto at = [&](int i, int j) { return (i % segments) * rings + (j % rings); };
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < rings; ++j) {
            const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            out.faces.push_back({a, c, b});
            out.faces.push_back({a, d, c});
        }
}

}  // namespace

scene::Polyhedron torus(double major, double minor, int segments, int rings) {
    scene::Polyhedron out;
    const double tau = 2.0 * std::numbers::pi;
    for (int i = 0; i < segments; ++i) {
        const double u = tau * i / segments;
        for (int j = 0; j < rings; ++j) {
            const double v = tau * j / rings;
            const double r = major + minor * std::cos(v);
            out.points.emplace_back(r * std::cos(u), r * std::sin(u), minor * std::sin(v));
        }
    }
    addTubeFaces(out, segments, rings);
    return out;
}

glm::dvec3 torusKnotPoint(double scale, double t) {
    const double r = 2.0 + std::cos(3.0 * t);
    return scale * glm::dvec3(r * std::cos(2.0 * t), r * std::sin(2.0 * t), -std::sin(3.0 * t));
}

scene::Polyhedron torusKnot(double scale, double tube, int segments, int rings) {
    auto curve = [scale](double t) { return torusKnotPoint(scale, t); };
    scene::Polyhedron out;
    const double tau = 2.0 * std::numbers::pi;
    for (int i = 0; i < segments; ++i) {
        const double t = tau * i / segments;
        const glm::dvec3 p = curve(t);
        const glm::dvec3 tangent = glm::normalize(curve(t + 1e-4) - curve(t - 1e-4));
        // The frame leans on the position vector, which is periodic, so the
        // tube closes without the twist a parallel-transported frame leaves.
        const glm::dvec3 normal = glm::normalize(p - glm::dot(p, tangent) * tangent);
        // normal x tangent, not tangent x normal: keeps (i, j) counter-clockwise outside.
        const glm::dvec3 binormal = glm::cross(normal, tangent);
        for (int j = 0; j < rings; ++j) {
            const double v = tau * j / rings;
            out.points.push_back(p + tube * (std::cos(v) * normal + std::sin(v) * binormal));
        }
    }
    addTubeFaces(out, segments, rings);
    return out;
}

}  // namespace strata::bench
