#pragma once
// A closed triangle mesh: the form every leaf takes before it reaches the GPU
// or the reference ray caster. Plain arrays, no OpenMesh in the interface.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace strata::mesh {

struct Mesh {
    std::vector<glm::dvec3> positions;                // V: #V points
    std::vector<std::array<uint32_t, 3>> triangles;   // F: #F triangles, counter-clockwise seen from outside
};

struct Bounds {
    glm::dvec3 min{1e300, 1e300, 1e300};
    glm::dvec3 max{-1e300, -1e300, -1e300};
    bool empty() const { return min.x > max.x; }
    void extend(const glm::dvec3& p);
    void extend(const Bounds& b);
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double diagonal() const;
};

Bounds boundsOf(const Mesh& mesh);

// Applies `transform` (to column vectors) to every position. A transform with a
// negative determinant (a mirror) also reverses every triangle, so the mesh
// stays outward oriented.
Mesh transformed(const Mesh& mesh, const glm::dmat4& transform);

// `mesh` in an order that depends on its geometry alone: points by position
// (x, then y, then z; points at one position in the order they came), each
// triangle turned to start at its least point (its orientation kept),
// triangles in order of their points. CGAL's containers order elements by
// where they were allocated, which moves with the allocator and with what
// other threads allocate, so one result could otherwise be written in
// several orders.
void canonicalOrder(Mesh& mesh);

}  // namespace strata::mesh
