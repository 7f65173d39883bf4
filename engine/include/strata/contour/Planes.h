#pragma once
// The planes the sampled solid's faces lie on, for a contour that rebuilds
// flat regions on them (Contour.h). Every leaf of a CSG model is a
// polyhedron, so every point of the result's surface lies on the plane of
// some leaf triangle, facing outward or (a subtracted leaf) inward; the
// table holds each such plane once per facing and finds the plane a
// crossing of the sampled image lies on.

#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/mesh/Mesh.h"

namespace strata::contour {

// An oriented plane: the points x with dot(normal, x) == offset; normal unit.
struct Plane {
    glm::dvec3 normal{0.0};
    double offset = 0.0;
};

class PlaneTable {
public:
    // Normals within this angle (about 0.3 degrees) count as one direction
    // when a crossing is matched; its position decides among them.
    static constexpr double kNormalMatch = 0.99998;

    PlaneTable() = default;

    // The planes of every triangle of `meshes` (degenerate ones skipped),
    // each in both facings; triangles on one plane (to within 1e-7 of the
    // meshes' extent) share it.
    static PlaneTable fromMeshes(std::span<const mesh::Mesh> meshes);

    // Adds `plane` in both facings, unless it is there already; returns its
    // id (the facing given).
    std::int32_t add(const Plane& plane);

    // Whether `point`, on plane `id`, lies within `tolerance` of one of the
    // triangles fromMeshes found on it (false for planes given to add).
    bool onTriangle(std::int32_t id, const glm::dvec3& point, double tolerance) const;

    std::size_t size() const { return planes_.size(); }
    const Plane& operator[](std::int32_t id) const { return planes_[std::size_t(id)]; }

    // For a point that plane `id` holds on no triangle of its own but that
    // lies within `reach` of it, just past one of its triangles' edges: the
    // plane of the leaf triangle across that edge, in the facing `id` has
    // relative to its triangle, if it holds `point` on one of its triangles
    // within `tolerance`; else -1. (A sampler may name the facet across a
    // ridge for a point on the ridge's other side.)
    std::int32_t acrossEdge(std::int32_t id, const glm::dvec3& point, double reach, double tolerance) const;
    // The plane whose facing agrees with `normal` (a unit vector, within
    // kNormalMatch) and that passes nearest `point`, if within `tolerance`;
    // else -1.
    std::int32_t find(const glm::dvec3& point, const glm::dvec3& normal, double tolerance) const;

private:
    using Key = std::uint64_t;
    static Key keyOf(const glm::ivec3& cell);
    static glm::ivec3 cellOf(const glm::dvec3& normal);
    // Calls visitPlane(id) for each plane whose normal is in the bucket of
    // `normal` or a neighbouring one and whose offset is in [low, high].
    template <typename Visit>
    void visit(const glm::dvec3& normal, double low, double high, Visit&& visitPlane) const;
    void insert(const Plane& plane);

    std::vector<Plane> planes_;
    // A leaf triangle as onTriangle tests it: corners, unit normal, box;
    // the id of its plane in its own (outward) facing, and of the plane of
    // the triangle across each edge (corners e, e + 1) in that one's, -1
    // where that is the same plane or there is none.
    struct Triangle {
        std::array<glm::dvec3, 3> corners;
        glm::dvec3 normal;
        glm::dvec3 low, high;
        std::int32_t facing = -1;
        std::array<std::int32_t, 3> across{-1, -1, -1};
    };
    // Per plane pair (id / 2, both facings): its triangles.
    std::vector<std::vector<Triangle>> triangles_;
    // Planes by the cell of their normal on a grid over [-1, 1]³.
    std::unordered_map<Key, std::vector<std::int32_t>> byDirection_;
    double mergeTolerance_ = 0.0;
};

}  // namespace strata::contour
