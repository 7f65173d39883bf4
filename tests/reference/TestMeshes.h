#pragma once
// Meshes for the reference tests, built here rather than by engine/geometry so
// the tests stand on their own: an axis-aligned box, OpenSCAD 2021.01's sphere
// (rings of n vertices, flat caps, no poles), mirroring, and a way to pack
// leaves into a scene::Tree and a model::Model.

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::reference::test {

inline mesh::Mesh box(const glm::dvec3& lo, const glm::dvec3& hi) {
    mesh::Mesh mesh;
    for (int k = 0; k < 8; ++k) {
        mesh.positions.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    }
    // Each face as a quad, counter-clockwise seen from outside.
    const uint32_t quads[6][4] = {
        {0, 2, 3, 1},  // z = lo
        {4, 5, 7, 6},  // z = hi
        {0, 1, 5, 4},  // y = lo
        {2, 6, 7, 3},  // y = hi
        {0, 4, 6, 2},  // x = lo
        {1, 3, 7, 5},  // x = hi
    };
    for (const auto& q : quads) {
        mesh.triangles.push_back({q[0], q[1], q[2]});
        mesh.triangles.push_back({q[0], q[2], q[3]});
    }
    return mesh;
}

// OpenSCAD 2021.01's sphere with n fragments: floor((n+1)/2) rings, ring i at
// polar angle 180*(i+0.5)/rings, vertex k at 360*k/n from +X. Caps are fans
// from the ring's first vertex, so a ray down the axis meets a shared edge.
inline mesh::Mesh sphere(double r, int n, const glm::dvec3& centre = glm::dvec3(0.0)) {
    const double pi = std::numbers::pi;
    const int rings = (n + 1) / 2;
    mesh::Mesh mesh;
    for (int i = 0; i < rings; ++i) {
        const double phi = pi * (i + 0.5) / rings;
        for (int k = 0; k < n; ++k) {
            const double theta = 2.0 * pi * k / n;
            mesh.positions.push_back(centre + glm::dvec3(r * std::sin(phi) * std::cos(theta),
                                                         r * std::sin(phi) * std::sin(theta), r * std::cos(phi)));
        }
    }
    auto at = [n](int ring, int k) { return static_cast<uint32_t>(ring * n + (k % n)); };
    for (int k = 1; k + 1 < n; ++k) {
        mesh.triangles.push_back({at(0, 0), at(0, k), at(0, k + 1)});                  // top, facing +Z
        mesh.triangles.push_back({at(rings - 1, 0), at(rings - 1, k + 1), at(rings - 1, k)});  // bottom
    }
    for (int i = 0; i + 1 < rings; ++i) {
        for (int k = 0; k < n; ++k) {
            mesh.triangles.push_back({at(i, k), at(i + 1, k), at(i + 1, k + 1)});
            mesh.triangles.push_back({at(i, k), at(i + 1, k + 1), at(i, k + 1)});
        }
    }
    return mesh;
}

// The height of the flat top cap of sphere(r, n) above its centre.
inline double capHeight(double r, int n) {
    const int rings = (n + 1) / 2;
    return r * std::cos(std::numbers::pi * 0.5 / rings);
}

// Mirror in the plane `axis` = 0; the winding is reversed so it stays outward.
inline mesh::Mesh mirrored(mesh::Mesh mesh, int axis) {
    for (auto& p : mesh.positions) p[axis] = -p[axis];
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

inline double signedVolume(const mesh::Mesh& mesh) {
    double v = 0.0;
    for (const auto& t : mesh.triangles) {
        v += glm::dot(mesh.positions[t[0]], glm::cross(mesh.positions[t[1]], mesh.positions[t[2]])) / 6.0;
    }
    return v;
}

// A tree and its model built side by side: leaf(mesh) returns the node index.
struct SceneBuilder {
    scene::Tree tree;
    model::Model model;

    int leaf(mesh::Mesh mesh, scene::Display display = scene::Display::Normal) {
        scene::Leaf leaf;
        leaf.display = display;
        model.leafMeshes.push_back(std::move(mesh));
        return tree.addLeaf(std::move(leaf));
    }
    int node(scene::NodeKind kind, std::vector<int> children) { return tree.addNode(kind, std::move(children)); }
    int unite(std::vector<int> children) { return node(scene::NodeKind::Union, std::move(children)); }
    int intersect(std::vector<int> children) { return node(scene::NodeKind::Intersection, std::move(children)); }
    int subtract(std::vector<int> children) { return node(scene::NodeKind::Difference, std::move(children)); }
    void setRoot(int root) { tree.root = root; }
};

}  // namespace strata::reference::test
