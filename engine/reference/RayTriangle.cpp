#include "strata/reference/RayTriangle.h"

#include <cmath>

#include <glm/geometric.hpp>

// This file must be compiled without floating-point contraction (see
// CMakeLists.txt): orient() relies on a*b - c*d rounding the same way in both
// argument orders, which a fused multiply-add would break.

namespace strata::reference {

namespace {

// orient(O, a, b) for O at the origin of the plane: twice the signed area of (O, a, b).
double orient(const glm::dvec3& a, const glm::dvec3& b) { return a.x * b.y - a.y * b.x; }

// The sign orient(O + (eps, eps^2), a, b) has for an infinitesimal eps > 0 when
// orient(O, a, b) == 0: d/dO of orient is (a.y - b.y, b.x - a.x).
int tieSign(const glm::dvec3& a, const glm::dvec3& b) {
    if (a.y != b.y) return a.y > b.y ? 1 : -1;
    if (a.x != b.x) return b.x > a.x ? 1 : -1;
    return 0;  // a == b in the plane: a degenerate edge
}

int edgeSign(double e, const glm::dvec3& a, const glm::dvec3& b) {
    if (e > 0.0) return 1;
    if (e < 0.0) return -1;
    return tieSign(a, b);
}

}  // namespace

RayFrame::RayFrame(const camera::Ray& ray) : ray_{ray.origin, glm::normalize(ray.direction)} {
    const glm::dvec3 d = ray_.direction;
    const glm::dvec3 m = glm::abs(d);
    glm::dvec3 axis{0.0};
    if (m.x <= m.y && m.x <= m.z) axis.x = 1.0;
    else if (m.y <= m.z) axis.y = 1.0;
    else axis.z = 1.0;
    b1_ = glm::normalize(glm::cross(axis, d));
    b2_ = glm::cross(d, b1_);
}

glm::dvec3 RayFrame::project(const glm::dvec3& p) const {
    const glm::dvec3 q = p - ray_.origin;
    return {glm::dot(q, b1_), glm::dot(q, b2_), glm::dot(q, ray_.direction)};
}

std::optional<TriangleCrossing> crossProjected(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // Weights of a, b, c: the orientation of O against the opposite edge.
    const double ea = orient(b, c), eb = orient(c, a), ec = orient(a, b);
    const int sa = edgeSign(ea, b, c), sb = edgeSign(eb, c, a), sc = edgeSign(ec, a, b);
    if (sa == 0 || sa != sb || sb != sc) return std::nullopt;
    const double det = ea + eb + ec;  // twice the projected area: dot(normal, direction) * 2|area|
    if (det == 0.0 || !std::isfinite(det)) return std::nullopt;
    // With b1 x b2 = direction, a counter-clockwise (outward) triangle whose
    // normal points along the ray projects counter-clockwise: all signs positive.
    TriangleCrossing crossing;
    crossing.t = (ea * a.z + eb * b.z + ec * c.z) / det;
    crossing.entering = sa < 0;
    return crossing;
}

std::optional<TriangleCrossing> crossTriangle(const RayFrame& frame, const glm::dvec3& a, const glm::dvec3& b,
                                              const glm::dvec3& c) {
    return crossProjected(frame.project(a), frame.project(b), frame.project(c));
}

}  // namespace strata::reference
