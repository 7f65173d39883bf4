// The renderer against a brute-force ray caster written here, on random CSG
// scenes seen from random cameras, the eye inside the scene included.
//
// The oracle shares nothing with the GPU path but the contract's camera: per
// pixel it intersects the contract's ray with every triangle of every leaf
// (Möller–Trumbore, double precision), sorts the hits, starts each leaf
// inside when an odd number of its hits lie ahead of the ray start, and
// walks the hits, reading the tree recursively after each, until the
// result's membership changes. Pixels whose ray passes within a small margin
// of a triangle edge are ambiguous (either face may be "the" hit), and so
// are pixels with two hits closer than the coincidence tolerance (the
// renderer takes them as one place, Camera.h: the oracle does not know that
// rule, and the accuracy corpus's coincident family checks it); they are
// left out. Every other pixel must agree in coverage, leaf, depth and normal.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "strata/model/Model.h"
#include "SphereShells.h"
#include "strata/gpu/Context.h"
#include "strata/render/Renderer.h"

using namespace strata;
using scene::NodeKind;

namespace {

struct OracleHit {
    double depth = 0.0;
    int leaf = -1;
    bool entry = false;
    glm::dvec3 normal{0.0};
};

struct OraclePixel {
    double depth = std::numeric_limits<double>::infinity();
    int leaf = -1;
    glm::dvec3 normal{0.0};
    bool ambiguous = false;  // the ray passes close to an edge, or hits coincide
};

bool member(const scene::Tree& tree, int node, const std::vector<char>& inside) {
    const scene::Node& n = tree.nodes[static_cast<std::size_t>(node)];
    switch (n.kind) {
        case NodeKind::Leaf: return inside[static_cast<std::size_t>(n.leaf)] != 0;
        case NodeKind::Union:
            return std::any_of(n.children.begin(), n.children.end(), [&](int c) { return member(tree, c, inside); });
        case NodeKind::Intersection:
            return !n.children.empty() &&
                   std::all_of(n.children.begin(), n.children.end(), [&](int c) { return member(tree, c, inside); });
        case NodeKind::Difference: {
            if (n.children.empty() || !member(tree, n.children[0], inside)) return false;
            for (std::size_t i = 1; i < n.children.size(); ++i) {
                if (member(tree, n.children[i], inside)) return false;
            }
            return true;
        }
    }
    return false;
}

class Oracle {
public:
    Oracle(const scene::Tree& tree, const model::Model& model) : tree_(tree), model_(model) {
        for (const mesh::Mesh& m : model.leafMeshes) bounds_.push_back(mesh::boundsOf(m));
    }

    OraclePixel trace(const camera::Camera& camera, int i, int j, double coincidence) const {
        const camera::Ray ray = camera.ray(i, j);
        const glm::dvec3 f = camera.forward();
        const double startDepth = glm::dot(ray.origin - camera.eye, f);  // 0 for both projections
        std::vector<OracleHit> hits;
        bool ambiguous = false;
        const std::size_t leaves = model_.leafMeshes.size();
        std::vector<char> inside(leaves, 0);
        for (std::size_t l = 0; l < leaves; ++l) {
            if (!slabHit(ray, bounds_[l])) continue;
            const mesh::Mesh& mesh = model_.leafMeshes[l];
            for (const auto& t : mesh.triangles) {
                const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
                double s, u, v;
                if (!intersect(ray, a, b, c, s, u, v)) continue;
                if (std::min({u, v, 1.0 - u - v}) < kEdgeMargin) ambiguous = true;
                const double depth = glm::dot(ray.origin + s * ray.direction - camera.eye, f);
                if (depth <= startDepth) continue;
                const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
                hits.push_back({depth, static_cast<int>(l), glm::dot(n, ray.direction) < 0.0, n});
                inside[l] ^= 1;  // odd number of hits ahead: inside at the start
            }
        }
        std::sort(hits.begin(), hits.end(), [](const OracleHit& x, const OracleHit& y) { return x.depth < y.depth; });
        OraclePixel out;
        bool result = member(tree_, tree_.root, inside);
        for (std::size_t h = 0; h < hits.size(); ++h) {
            if (h + 1 < hits.size() && hits[h + 1].depth - hits[h].depth <= coincidence) ambiguous = true;
            inside[static_cast<std::size_t>(hits[h].leaf)] = hits[h].entry ? 1 : 0;
            const bool now = member(tree_, tree_.root, inside);
            if (now != result) {
                out.depth = hits[h].depth;
                out.leaf = hits[h].leaf;
                out.normal = hits[h].entry == now ? hits[h].normal : -hits[h].normal;
                break;
            }
            result = now;
        }
        out.ambiguous = ambiguous;
        return out;
    }

private:
    // Barycentric distance from an edge below which a hit counts as "on the edge".
    static constexpr double kEdgeMargin = 2e-3;

    static bool slabHit(const camera::Ray& ray, const mesh::Bounds& b) {
        double t0 = -1e300, t1 = 1e300;
        for (int k = 0; k < 3; ++k) {
            if (std::abs(ray.direction[k]) < 1e-300) {
                if (ray.origin[k] < b.min[k] || ray.origin[k] > b.max[k]) return false;
                continue;
            }
            double a = (b.min[k] - ray.origin[k]) / ray.direction[k];
            double c = (b.max[k] - ray.origin[k]) / ray.direction[k];
            if (a > c) std::swap(a, c);
            t0 = std::max(t0, a);
            t1 = std::min(t1, c);
        }
        return t0 <= t1 + 1e-9 && t1 >= -1e-9;
    }

    // Möller–Trumbore; s along the ray (may be negative: the caller filters by depth).
    static bool intersect(const camera::Ray& ray, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                          double& s, double& u, double& v) {
        const glm::dvec3 e1 = b - a, e2 = c - a;
        const glm::dvec3 p = glm::cross(ray.direction, e2);
        const double det = glm::dot(e1, p);
        if (std::abs(det) < 1e-14) return false;
        const glm::dvec3 tv = ray.origin - a;
        u = glm::dot(tv, p) / det;
        if (u < 0.0 || u > 1.0) return false;
        const glm::dvec3 q = glm::cross(tv, e1);
        v = glm::dot(ray.direction, q) / det;
        if (v < 0.0 || u + v > 1.0) return false;
        s = glm::dot(e2, q) / det;
        return true;
    }

    const scene::Tree& tree_;
    const model::Model& model_;
    std::vector<mesh::Bounds> bounds_;
};

// A polyhedron of a few sphere shells in a row: a non-convex operand that
// needs more than one peel layer.
scene::Polyhedron shells(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const glm::dvec3 step = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 0.8;
    const int count = 2 + static_cast<int>(rng() % 2);
    std::vector<glm::dvec3> centres;
    for (int k = 0; k < count; ++k)
        centres.push_back(step * (k - 0.5 * (count - 1)) * (1.0 / std::max(0.5, glm::length(step))));
    return test::sphereShells(centres, 0.35, 10);
}

scene::Primitive randomPrimitive(std::mt19937& rng) {
    std::uniform_real_distribution<double> size(0.5, 1.8);
    switch (rng() % 4) {
        case 0: return scene::Cube{{size(rng), size(rng), size(rng)}, true};
        case 1: {
            scene::Sphere s;
            s.r = size(rng) * 0.6;
            s.fragments.fn = 6 + static_cast<double>(rng() % 12);
            return s;
        }
        case 2: {
            scene::Cylinder c;
            c.h = size(rng) * 1.5;
            c.r1 = size(rng) * 0.5;
            c.r2 = (rng() % 3 == 0) ? 0.0 : size(rng) * 0.5;
            c.center = true;
            c.fragments.fn = 5 + static_cast<double>(rng() % 12);
            return c;
        }
        default: return shells(rng);
    }
}

scene::Leaf randomLeaf(std::mt19937& rng) {
    std::uniform_real_distribution<double> pos(-1.2, 1.2), angle(0.0, 360.0);
    scene::Leaf leaf{randomPrimitive(rng), glm::dmat4(1.0), std::nullopt, scene::Display::Normal, {}, nullptr};
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), {pos(rng), pos(rng), pos(rng)});
    m = glm::rotate(m, glm::radians(angle(rng)), glm::normalize(glm::dvec3(pos(rng), pos(rng), pos(rng) + 0.01)));
    leaf.transform = m;
    return leaf;
}

int randomTree(scene::Tree& tree, std::mt19937& rng, int depth) {
    if (depth == 0 || rng() % 4 == 0) return tree.addLeaf(randomLeaf(rng));
    const NodeKind kinds[] = {NodeKind::Union, NodeKind::Intersection, NodeKind::Difference, NodeKind::Difference};
    const NodeKind kind = kinds[rng() % 4];
    std::vector<int> children;
    const int arity = 2 + static_cast<int>(rng() % 2);
    for (int c = 0; c < arity; ++c) children.push_back(randomTree(tree, rng, depth - 1));
    return tree.addNode(kind, children);
}

}  // namespace

TEST(RendererOracle, RandomScenesAgreeWithABruteForceRayCaster) {
    gpu::Context context;
    render::Renderer renderer;
    std::mt19937 rng(1234567);
    constexpr int kScenes = 24;
    constexpr int kSize = 48;
    std::size_t compared = 0, hits = 0, ambiguousTotal = 0, disagreeTotal = 0;
    for (int s = 0; s < kScenes; ++s) {
        scene::Tree tree;
        tree.root = randomTree(tree, rng, 4);
        const model::Model model = model::buildModel(tree);
        renderer.setScene(tree, model);
        const Oracle oracle(tree, model);
        const double diagonal = model.bounds.empty() ? 1.0 : model.bounds.diagonal();

        for (int c = 0; c < 3; ++c) {
            camera::Camera camera;
            std::uniform_real_distribution<double> unit(-1.0, 1.0);
            glm::dvec3 dir;
            do dir = {unit(rng), unit(rng), unit(rng)};
            while (glm::length(dir) < 0.3 || std::abs(glm::normalize(dir).z) > 0.95);
            dir = glm::normalize(dir);
            // Camera 2 sits inside the scene's box, so the near plane cuts the model.
            camera.eye = c == 2 ? glm::dvec3(unit(rng), unit(rng), unit(rng)) * 0.5 : dir * (6.0 + 3.0 * unit(rng));
            camera.center = c == 2 ? camera.eye - dir : glm::dvec3(0.0);
            camera.projection = c == 1 ? camera::Projection::Orthographic : camera::Projection::Perspective;
            camera.fovDegrees = c == 2 ? 70.0 : 30.0;
            if (c == 1) {  // orthographic: half-height |C - E| tan(fov/2) = 4 tan(30°) ~ 2.3
                camera.center = camera.eye - dir * 4.0;
                camera.fovDegrees = 60.0;
            }
            camera.width = kSize;
            camera.height = kSize;
            const render::Frame frame = renderer.render(camera, {});
            const double coincidence = camera::coincidenceTolerance(camera, model.bounds);

            std::size_t disagree = 0, ambiguous = 0;
            for (int j = 0; j < kSize; ++j) {
                for (int i = 0; i < kSize; ++i) {
                    const OraclePixel want = oracle.trace(camera, i, j, coincidence);
                    const std::size_t k = static_cast<std::size_t>(j * kSize + i);
                    if (want.ambiguous) {
                        ++ambiguous;
                        continue;
                    }
                    ++compared;
                    hits += want.leaf >= 0 ? 1 : 0;
                    bool same = frame.leaf[k] == want.leaf;
                    if (same && want.leaf >= 0) {
                        same = std::abs(frame.depth[k] - want.depth) <= 1e-4 * diagonal &&
                               glm::dot(glm::dvec3(frame.normal[k]), want.normal) > std::cos(glm::radians(1.0));
                    }
                    if (!same) {
                        if (disagree < 3) {
                            ADD_FAILURE() << "scene " << s << " camera " << c << " pixel " << i << "," << j
                                          << ": gpu leaf " << frame.leaf[k] << " depth " << frame.depth[k]
                                          << " normal " << frame.normal[k].x << "," << frame.normal[k].y << ","
                                          << frame.normal[k].z << "; oracle leaf " << want.leaf << " depth "
                                          << want.depth << " normal " << want.normal.x << "," << want.normal.y
                                          << "," << want.normal.z;
                        }
                        ++disagree;
                    }
                }
            }
            ambiguousTotal += ambiguous;
            disagreeTotal += disagree;
        }
    }
    std::printf("oracle: %zu pixels compared (%zu hits), %zu near edges left out, %zu disagree\n", compared, hits,
                ambiguousTotal, disagreeTotal);
    EXPECT_EQ(disagreeTotal, 0u);
    EXPECT_GT(hits, compared / 10);  // the scenes are not mostly empty
}
