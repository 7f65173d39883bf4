#include "Scenes.h"

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "Solids.h"
#include "strata/core/Error.h"
#include "strata/mesh/Mesh.h"

namespace strata::bench {
namespace {

using scene::Leaf;
using scene::NodeKind;
using scene::Tree;

// $fn=32 gives OpenSCAD's sphere 32 segments and 16 rings.
constexpr double kSphereFn = 32.0;

int addSphere(Tree& tree, const glm::dvec3& center, double r) {
    Leaf leaf;
    scene::Sphere sphere;
    sphere.r = r;
    sphere.fragments.fn = kSphereFn;
    leaf.primitive = sphere;
    leaf.transform = glm::translate(glm::dmat4(1.0), center);
    return tree.addLeaf(std::move(leaf));
}

int addPolyhedron(Tree& tree, const scene::Polyhedron& polyhedron, const glm::dmat4& transform) {
    Leaf leaf;
    leaf.primitive = polyhedron;
    leaf.transform = transform;
    return tree.addLeaf(std::move(leaf));
}

int addCube(Tree& tree, const glm::dvec3& center, const glm::dvec3& size) {
    Leaf leaf;
    leaf.primitive = scene::Cube{size, true};
    leaf.transform = glm::translate(glm::dmat4(1.0), center);
    return tree.addLeaf(std::move(leaf));
}

// A 10-unit cube with K spheres of radius 0.6..1.4 centred anywhere in it or
// just outside, so most of them cut its faces.
Tree cheese(int k, std::mt19937& rng) {
    Tree tree;
    std::uniform_real_distribution<double> pos(-5.5, 5.5), radius(0.6, 1.4);
    std::vector<int> children{addCube(tree, {0, 0, 0}, {10, 10, 10})};
    for (int i = 0; i < k; ++i) {
        const glm::dvec3 c{pos(rng), pos(rng), pos(rng)};
        children.push_back(addSphere(tree, c, radius(rng)));
    }
    tree.root = tree.addNode(NodeKind::Difference, std::move(children));
    return tree;
}

// A 12 x 12 x 3 slab; K spheres of radius 0.5 centred on the view ray through
// the slab's centre, evenly spread over 8 units of it, so they overlap once
// K > 8 and many stick out of both faces.
BenchScene stack(int k, const camera::Camera& base) {
    BenchScene out;
    Tree& tree = out.tree;
    std::vector<int> children{addCube(tree, {0, 0, 0}, {12, 12, 3})};
    mesh::Bounds slab;
    slab.extend(glm::dvec3(-6, -6, -1.5));
    slab.extend(glm::dvec3(6, 6, 1.5));
    const camera::Camera camera = camera::defaultCamera(slab, base);
    const glm::dvec3 f = camera.forward();
    const glm::dvec3 c = camera.center;
    for (int i = 0; i < k; ++i) {
        const double t = k == 1 ? 0.0 : -4.0 + 8.0 * i / (k - 1);
        children.push_back(addSphere(tree, c + t * f, 0.5));
    }
    tree.root = tree.addNode(NodeKind::Difference, std::move(children));
    out.camera = camera;
    return out;
}

// K spheres of radius 5, centres within 0.5 of the origin, intersected: a
// lens-shaped solid whose surface is a patchwork of all K.
Tree intersection(int k, std::mt19937& rng) {
    Tree tree;
    std::uniform_real_distribution<double> offset(-0.5, 0.5);
    std::vector<int> children;
    for (int i = 0; i < k; ++i)
        children.push_back(addSphere(tree, {offset(rng), offset(rng), offset(rng)}, 5.0));
    tree.root = tree.addNode(NodeKind::Intersection, std::move(children));
    return tree;
}

// Leaf 0 is a 10-unit cube; then each leaf i joins the chain as
//   union (i % 4 == 1, 3), difference (i % 4 == 2), intersection (i % 8 == 0)
// where an intersection's operand is a large sphere that keeps most of the
// chain. Other leaves are spheres and cubes of size 1..3 in a 12-unit box.
Tree deep(int k, std::mt19937& rng) {
    Tree tree;
    std::uniform_real_distribution<double> pos(-6.0, 6.0), size(1.0, 3.0);
    int node = addCube(tree, {0, 0, 0}, {10, 10, 10});
    for (int i = 1; i < k; ++i) {
        NodeKind kind = NodeKind::Union;
        int leaf = -1;
        if (i % 8 == 0) {
            kind = NodeKind::Intersection;
            leaf = addSphere(tree, {0, 0, 0}, 9.0);
        } else {
            kind = i % 4 == 2 ? NodeKind::Difference : NodeKind::Union;
            const glm::dvec3 c{pos(rng), pos(rng), pos(rng)};
            const double s = size(rng);
            leaf = i % 2 == 0 ? addSphere(tree, c, s / 2) : addCube(tree, c, {s, s, s});
        }
        node = tree.addNode(kind, {node, leaf});
    }
    tree.root = node;
    return tree;
}

// The cheese's cube with K tori (major radius 0.8..1.6, tube 0.3 of that,
// 32 segments x 16 rings) centred anywhere in it or just outside, each turned
// about a random axis, so rays cross up to 4 of each torus's surfaces.
Tree tori(int k, std::mt19937& rng) {
    Tree tree;
    const scene::Polyhedron unit = torus(1.0, 0.3, 32, 16);
    std::uniform_real_distribution<double> pos(-5.5, 5.5), scale(0.8, 1.6), angle(0.0, 6.283185307179586),
        axis(-1.0, 1.0);
    std::vector<int> children{addCube(tree, {0, 0, 0}, {10, 10, 10})};
    for (int i = 0; i < k; ++i) {
        const glm::dvec3 c{pos(rng), pos(rng), pos(rng)};
        glm::dvec3 a{axis(rng), axis(rng), axis(rng)};
        if (glm::length(a) < 1e-3) a = {0, 0, 1};
        glm::dmat4 m = glm::translate(glm::dmat4(1.0), c);
        m = glm::rotate(m, angle(rng), glm::normalize(a));
        m = glm::scale(m, glm::dvec3(scale(rng)));
        children.push_back(addPolyhedron(tree, unit, m));
    }
    tree.root = tree.addNode(NodeKind::Difference, std::move(children));
    return tree;
}

// A trefoil-knot tube (curve scale 3, tube radius 1.2; 1024 x 64 quads:
// 131072 triangles) minus K spheres of radius 0.5..1.0 centred 0.6..1.2 tube
// radii from the curve at random points along it, so most bite the tube.
Tree mesh(int k, std::mt19937& rng) {
    constexpr double kScale = 3.0, kTube = 1.2;
    Tree tree;
    std::vector<int> children{addPolyhedron(tree, torusKnot(kScale, kTube, 1024, 64), glm::dmat4(1.0))};
    std::uniform_real_distribution<double> t(0.0, 6.283185307179586), away(0.6 * kTube, 1.2 * kTube),
        direction(-1.0, 1.0), radius(0.5, 1.0);
    for (int i = 0; i < k; ++i) {
        glm::dvec3 d{direction(rng), direction(rng), direction(rng)};
        if (glm::length(d) < 1e-3) d = {0, 0, 1};
        const glm::dvec3 c = torusKnotPoint(kScale, t(rng)) + away(rng) * glm::normalize(d);
        children.push_back(addSphere(tree, c, radius(rng)));
    }
    tree.root = tree.addNode(NodeKind::Difference, std::move(children));
    return tree;
}

// K unions of two spheres of radius 5, intersected. The spheres' centres lie
// 1 unit either side of a point within 0.5 of the origin, along a random
// direction, so every box overlaps every other and no product is pruned:
// the sum of products is 2^K products of K spheres each.
Tree blowup(int k, std::mt19937& rng) {
    Tree tree;
    std::uniform_real_distribution<double> offset(-0.5, 0.5), direction(-1.0, 1.0);
    std::vector<int> unions;
    for (int i = 0; i < k; ++i) {
        const glm::dvec3 c{offset(rng), offset(rng), offset(rng)};
        glm::dvec3 d{direction(rng), direction(rng), direction(rng)};
        if (glm::length(d) < 1e-3) d = {0, 0, 1};
        d = glm::normalize(d);
        unions.push_back(tree.addNode(NodeKind::Union, {addSphere(tree, c - d, 5.0), addSphere(tree, c + d, 5.0)}));
    }
    tree.root = tree.addNode(NodeKind::Intersection, std::move(unions));
    return tree;
}

}  // namespace

const std::vector<std::string>& sceneNames() {
    static const std::vector<std::string> names{"cheese", "stack", "intersection", "deep", "tori", "mesh", "blowup"};
    return names;
}

BenchScene makeScene(std::string_view name, int k, std::uint32_t seed, const camera::Camera& base) {
    if (k < 1) throw Error("strata-bench: K must be at least 1, got " + std::to_string(k));
    // One stream per (scene, K), so adding a scene or a K leaves the others unchanged.
    std::seed_seq seq{seed, static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(name.size()),
                      static_cast<std::uint32_t>(name.empty() ? 0 : name[0])};
    std::mt19937 rng(seq);
    BenchScene out;
    if (name == "cheese")
        out.tree = cheese(k, rng);
    else if (name == "stack")
        out = stack(k, base);
    else if (name == "intersection")
        out.tree = intersection(k, rng);
    else if (name == "deep")
        out.tree = deep(k, rng);
    else if (name == "tori")
        out.tree = tori(k, rng);
    else if (name == "mesh")
        out.tree = mesh(k, rng);
    else if (name == "blowup")
        out.tree = blowup(k, rng);
    else
        throw Error("strata-bench: unknown scene '" + std::string(name) +
                    "' (expected cheese, stack, intersection, deep, tori, mesh or blowup)");
    out.tree.source = std::string(name) + "-" + std::to_string(k);
    return out;
}

}  // namespace strata::bench
