#pragma once
// The reference's exact, watertight ray-triangle crossing test.
//
// Every point where a ray meets a closed mesh must be counted exactly once
// (a crossing) or an even number of times with alternating facing (a graze):
// one missed or doubled crossing flips inside and outside for the rest of the
// ray. Float tests with tolerances do neither reliably at shared edges and
// vertices, so this test works in double precision in the ray's own frame
// (the ray becomes the origin of a plane, each vertex a 2D point) and breaks
// ties as if the ray were moved by an infinitesimal, fixed offset
// (simulation of simplicity, as rasterizers' top-left rule does):
//
//         v2                 the ray pierces the plane at O = (0,0).
//        /  \                e_i = orient(O, v_j, v_k) for the edge opposite v_i;
//       / O  \               O is inside when all three agree in sign. An edge
//     v0 ---- v1             through O (e == 0) takes the sign that O + (eps, eps^2)
//                            would give, which depends only on the edge.
//
// Because each vertex is projected by the same arithmetic in every triangle
// and orient(O, a, b) is exactly antisymmetric in a and b, two triangles that
// share an edge always disagree about it: a ray through the edge is claimed by
// exactly one of them (or, at a silhouette fold, by both or neither, with
// opposite facing). The same holds around a vertex.

#include <optional>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"

namespace strata::reference {

// A ray and an orthonormal frame (b1, b2, direction), b1 x b2 = direction.
class RayFrame {
public:
    explicit RayFrame(const camera::Ray& ray);

    // p in the ray's frame: (dot(p - o, b1), dot(p - o, b2), dot(p - o, d)).
    // The third coordinate is the ray parameter of p's foot on the ray.
    glm::dvec3 project(const glm::dvec3& p) const;

    const camera::Ray& ray() const { return ray_; }

private:
    camera::Ray ray_;
    glm::dvec3 b1_, b2_;
};

struct TriangleCrossing {
    double t = 0.0;         // ray parameter of the crossing point
    bool entering = false;  // dot(outward normal, direction) < 0: the ray goes into the solid
};

// The crossing of the ray with triangle (a, b, c), given as points already in
// the ray's frame (RayFrame::project) and counter-clockwise seen from outside.
// Empty when the ray misses it (after the tie-break) or the triangle is seen
// edge-on. The ray is a whole line here: t may be negative.
std::optional<TriangleCrossing> crossProjected(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Same, from world-space vertices.
std::optional<TriangleCrossing> crossTriangle(const RayFrame& frame, const glm::dvec3& a, const glm::dvec3& b,
                                              const glm::dvec3& c);

}  // namespace strata::reference
