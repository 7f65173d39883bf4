#pragma once
// A non-convex operand for the render tests: one polyhedron leaf made of
// sphere shells, so that a ray through two of them meets four surfaces and
// the peel needs more than one layer.

#include <vector>

#include <glm/vec3.hpp>

#include "strata/mesh/Primitives.h"
#include "strata/scene/Tree.h"

namespace strata::test {

// Spheres of `radius` ($fn = `fn`) centred at `centres`, as one polyhedron.
inline scene::Polyhedron sphereShells(const std::vector<glm::dvec3>& centres, double radius, double fn) {
    scene::Sphere ball;
    ball.r = radius;
    ball.fragments.fn = fn;
    const mesh::Mesh mesh = mesh::tessellate(ball);
    scene::Polyhedron poly;
    for (const glm::dvec3& centre : centres) {
        const int base = static_cast<int>(poly.points.size());
        for (const glm::dvec3& p : mesh.positions) poly.points.push_back(p + centre);
        // OpenSCAD lists polyhedron faces clockwise seen from outside.
        for (const auto& t : mesh.triangles) {
            poly.faces.push_back({base + static_cast<int>(t[2]), base + static_cast<int>(t[1]),
                                  base + static_cast<int>(t[0])});
        }
    }
    return poly;
}

}  // namespace strata::test
