// The reference ray caster on scenes whose answer is known in closed form,
// and on a whole image against an independent brute-force caster written here.
//
// Spheres are OpenSCAD's polyhedra, so closed-form depths use their flat caps:
// a camera looking straight down the Z axis meets the top cap at exactly
// capHeight(r, n) above the centre (and the cap's fan puts a shared edge right
// under the centre pixel, which the caster must count once).

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "TestMeshes.h"
#include "strata/core/Error.h"
#include "strata/reference/RayCaster.h"

using namespace strata::reference;
using namespace strata::reference::test;
using strata::camera::Camera;
using strata::camera::Projection;

namespace {

constexpr float kInfF = std::numeric_limits<float>::infinity();
constexpr int kFragments = 16;  // 8 rings

// Looking straight down from height `height` onto the origin; odd size, so the
// centre pixel's ray is the Z axis.
Camera topCamera(double height, Projection projection = Projection::Perspective, int size = 33) {
    Camera camera;
    camera.eye = {0.0, 0.0, height};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = size;
    camera.height = size;
    camera.fovDegrees = 30.0;
    camera.projection = projection;
    return camera;
}

struct Pixel {
    float depth;
    glm::vec3 normal;
    int leaf;
};

Pixel centre(const ReferenceImage& image) {
    const std::size_t k = static_cast<std::size_t>(image.height / 2) * image.width + image.width / 2;
    return {image.depth[k], image.normal[k], image.leaf[k]};
}

void expectNormal(const glm::vec3& actual, const glm::vec3& expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-6);
    EXPECT_NEAR(actual.y, expected.y, 1e-6);
    EXPECT_NEAR(actual.z, expected.z, 1e-6);
}

}  // namespace

TEST(RayCaster, BoxFaceDepthIsExactOnEveryPixelItCovers) {
    SceneBuilder s;
    s.setRoot(s.leaf(box({-1, -1, -1}, {1, 1, 1})));
    Camera camera;
    camera.eye = {0.0, -10.0, 0.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = 41;
    camera.height = 31;
    camera.fovDegrees = 20.0;
    const ReferenceImage image = renderReference(s.tree, s.model, camera);
    ASSERT_EQ(image.width, 41);
    ASSERT_EQ(image.depth.size(), 41u * 31u);
    int covered = 0;
    for (int j = 0; j < camera.height; ++j) {
        for (int i = 0; i < camera.width; ++i) {
            // Seen from the axis, only the front face y = -1 (depth 9) shows.
            const auto ray = camera.ray(i, j);
            const glm::dvec3 p = ray.origin + (9.0 / ray.direction.y) * ray.direction;
            const double margin = std::min(1.0 - std::abs(p.x), 1.0 - std::abs(p.z));
            if (std::abs(margin) < 1e-9) continue;
            const std::size_t k = static_cast<std::size_t>(j) * camera.width + i;
            if (margin > 0) {
                EXPECT_NEAR(image.depth[k], 9.0f, 1e-5) << i << "," << j;
                expectNormal(image.normal[k], {0, -1, 0});
                EXPECT_EQ(image.leaf[k], 0);
                ++covered;
            } else {
                EXPECT_EQ(image.depth[k], kInfF) << i << "," << j;
                EXPECT_EQ(image.leaf[k], -1);
                expectNormal(image.normal[k], {0, 0, 0});
            }
        }
    }
    EXPECT_GT(covered, 100);
    EXPECT_LT(covered, 41 * 31);
}

TEST(RayCaster, CubeMinusSphereSeesTheInsideOfTheSphere) {
    // Cube [-1,1]^3 minus a sphere of radius 0.5 centred on the top face:
    // down the axis, the result begins at the sphere's bottom cap, whose
    // outward normal (0,0,-1) is flipped.
    SceneBuilder s;
    const int cube = s.leaf(box({-1, -1, -1}, {1, 1, 1}));
    const int ball = s.leaf(sphere(0.5, kFragments, {0, 0, 1}));
    s.setRoot(s.subtract({cube, ball}));
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Pixel p = centre(renderReference(s.tree, s.model, topCamera(10.0, projection)));
        EXPECT_NEAR(p.depth, 10.0 - (1.0 - capHeight(0.5, kFragments)), 1e-5);
        EXPECT_EQ(p.leaf, 1);
        expectNormal(p.normal, {0, 0, 1});
    }
}

TEST(RayCaster, IntersectionOfTwoSpheresBeginsAtTheLowerOnesCap) {
    SceneBuilder s;
    const int upper = s.leaf(sphere(1.0, kFragments, {0, 0, 0.5}));
    const int lower = s.leaf(sphere(1.0, kFragments, {0, 0, -0.5}));
    s.setRoot(s.intersect({upper, lower}));
    const Pixel p = centre(renderReference(s.tree, s.model, topCamera(10.0)));
    EXPECT_NEAR(p.depth, 10.0 - (-0.5 + capHeight(1.0, kFragments)), 1e-5);
    EXPECT_EQ(p.leaf, 1);
    expectNormal(p.normal, {0, 0, 1});
}

TEST(RayCaster, UnionShowsTheNearestOperand) {
    SceneBuilder s;
    const int cube = s.leaf(box({-1, -1, -1}, {1, 1, 1}));
    const int ball = s.leaf(sphere(0.75, kFragments, {0, 0, 1.25}));
    s.setRoot(s.unite({cube, ball}));
    const Pixel p = centre(renderReference(s.tree, s.model, topCamera(10.0, Projection::Orthographic)));
    EXPECT_NEAR(p.depth, 10.0 - (1.25 + capHeight(0.75, kFragments)), 1e-5);
    EXPECT_EQ(p.leaf, 1);
    expectNormal(p.normal, {0, 0, 1});
}

// The original paper's failure case: a slab minus three spheres lined up on
// the view ray. s1 and s2 overlap, s2 and s3 overlap, so the slab is carved
// through until s3's bottom cap, which is the visible surface.
TEST(RayCaster, SlabMinusThreeSpheresOnTheViewRay) {
    const double c3 = -0.5, r3 = 0.4;
    const double expected = 10.0 - (c3 - capHeight(r3, kFragments));
    for (bool asUnion : {false, true}) {
        SceneBuilder s;
        const int slab = s.leaf(box({-3, -3, -1}, {3, 3, 1}));
        const int s1 = s.leaf(sphere(0.5, kFragments, {0, 0, 1.2}));
        const int s2 = s.leaf(sphere(0.5, kFragments, {0, 0, 0.3}));
        const int s3 = s.leaf(sphere(r3, kFragments, {0, 0, c3}));
        s.setRoot(asUnion ? s.subtract({slab, s.unite({s1, s2, s3})}) : s.subtract({slab, s1, s2, s3}));
        for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
            const Pixel p = centre(renderReference(s.tree, s.model, topCamera(10.0, projection)));
            EXPECT_NEAR(p.depth, expected, 1e-5) << (asUnion ? "union" : "n-ary");
            EXPECT_EQ(p.leaf, 3);
            expectNormal(p.normal, {0, 0, 1});
        }
    }
}

TEST(RayCaster, MirroredLeavesKeepOutwardNormals) {
    // A box at x in [1, 3], mirrored to [-3, -1], seen from -X: its face x = -3 at depth 7.
    SceneBuilder s;
    const int a = s.leaf(mirrored(box({1, -1, -1}, {3, 1, 1}), 0));
    s.setRoot(a);
    Camera camera;
    camera.eye = {-10.0, 0.0, 0.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = camera.height = 9;
    Pixel p = centre(renderReference(s.tree, s.model, camera));
    EXPECT_NEAR(p.depth, 7.0, 1e-5);
    expectNormal(p.normal, {-1, 0, 0});

    // A mirrored subtrahend: [-4,0]^3-ish box minus the mirrored box [-3,-1] x [-.5,.5]^2 (grown in x).
    SceneBuilder d;
    const int big = d.leaf(box({-3.5, -2, -2}, {0, 2, 2}));
    const int cut = d.leaf(mirrored(box({0.5, -0.5, -0.5}, {3.75, 0.5, 0.5}), 0));  // x in [-3.75, -0.5]
    d.setRoot(d.subtract({big, cut}));
    p = centre(renderReference(d.tree, d.model, camera));
    EXPECT_NEAR(p.depth, 10.0 - 0.5, 1e-5);  // the cut's far face x = -0.5, flipped to face the eye
    EXPECT_EQ(p.leaf, 1);
    expectNormal(p.normal, {-1, 0, 0});
}

TEST(RayCaster, EyeInsideASubtractedOperand) {
    // Cube [-2,2]^3 minus a sphere around the eye (0,0,3): the ray starts inside
    // the sphere and outside the cube; the result begins at the sphere's bottom cap.
    SceneBuilder s;
    const int cube = s.leaf(box({-2, -2, -2}, {2, 2, 2}));
    const int ball = s.leaf(sphere(1.5, kFragments, {0, 0, 3}));
    s.setRoot(s.subtract({cube, ball}));
    const Pixel p = centre(renderReference(s.tree, s.model, topCamera(3.0)));
    EXPECT_NEAR(p.depth, capHeight(1.5, kFragments), 1e-5);
    EXPECT_EQ(p.leaf, 1);
    expectNormal(p.normal, {0, 0, 1});
}

TEST(RayCaster, RayStartingInsideTheResultSeesItsFirstExit) {
    SceneBuilder s;
    s.setRoot(s.leaf(box({-1, -1, -1}, {1, 1, 1})));
    // The eye in the cube.
    Pixel p = centre(renderReference(s.tree, s.model, topCamera(0.25)));
    EXPECT_NEAR(p.depth, 1.25, 1e-6);
    EXPECT_EQ(p.leaf, 0);
    expectNormal(p.normal, {0, 0, -1});
    // A near plane through the cube (depth 9.5 of 9..11): the same exit at depth 11.
    ReferenceOptions options;
    options.nearDepth = 9.5;
    p = centre(renderReference(s.tree, s.model, topCamera(10.0), options));
    EXPECT_NEAR(p.depth, 11.0, 1e-5);
    expectNormal(p.normal, {0, 0, -1});
    // A near plane beyond the model: nothing.
    options.nearDepth = 11.5;
    EXPECT_EQ(centre(renderReference(s.tree, s.model, topCamera(10.0), options)).leaf, -1);
}

TEST(RayCaster, NothingToDraw) {
    SceneBuilder s;
    const ReferenceImage empty = renderReference(s.tree, s.model, topCamera(10.0, Projection::Perspective, 5));
    for (float d : empty.depth) EXPECT_EQ(d, kInfF);
    for (int leaf : empty.leaf) EXPECT_EQ(leaf, -1);

    // A background leaf is drawn by the renderer but is not in the CSG.
    const int a = s.leaf(box({-1, -1, -1}, {1, 1, 1}), strata::scene::Display::Background);
    s.setRoot(s.unite({a}));
    EXPECT_EQ(centre(renderReference(s.tree, s.model, topCamera(10.0))).leaf, -1);

    s.model.leafMeshes.pop_back();
    EXPECT_THROW(ReferenceScene(s.tree, s.model), strata::Error);
}

namespace {

// An independent caster for the brute-force comparison: Moller-Trumbore on
// every triangle, parity per leaf, the tree evaluated at points between hits.
struct BruteHit {
    double t;
    int leaf;
    glm::dvec3 normal;
    double edge;  // the smallest barycentric coordinate: how close to an edge
};

bool memberAt(const strata::scene::Tree& tree, int node, const std::vector<bool>& in) {
    const auto& n = tree.nodes[static_cast<std::size_t>(node)];
    using strata::scene::NodeKind;
    switch (n.kind) {
        case NodeKind::Leaf: return in[static_cast<std::size_t>(n.leaf)];
        case NodeKind::Union:
            for (int c : n.children) {
                if (memberAt(tree, c, in)) return true;
            }
            return false;
        case NodeKind::Intersection:
            for (int c : n.children) {
                if (!memberAt(tree, c, in)) return false;
            }
            return !n.children.empty();
        case NodeKind::Difference:
            if (n.children.empty() || !memberAt(tree, n.children[0], in)) return false;
            for (std::size_t k = 1; k < n.children.size(); ++k) {
                if (memberAt(tree, n.children[k], in)) return false;
            }
            return true;
    }
    return false;
}

struct BruteResult {
    double t = std::numeric_limits<double>::infinity();
    int leaf = -1;
    glm::dvec3 normal{0.0};
    bool nearEdge = false;  // some hit on the ray is close to a triangle edge, or two hits nearly coincide
};

BruteResult bruteForce(const SceneBuilder& s, const strata::camera::Ray& ray) {
    std::vector<BruteHit> hits;
    for (std::size_t leaf = 0; leaf < s.model.leafMeshes.size(); ++leaf) {
        const auto& mesh = s.model.leafMeshes[leaf];
        for (const auto& tri : mesh.triangles) {
            const glm::dvec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
            const glm::dvec3 e1 = b - a, e2 = c - a;
            const glm::dvec3 pv = glm::cross(ray.direction, e2);
            const double det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-14) continue;
            const glm::dvec3 tv = ray.origin - a;
            const double u = glm::dot(tv, pv) / det;
            const glm::dvec3 qv = glm::cross(tv, e1);
            const double v = glm::dot(ray.direction, qv) / det;
            const double t = glm::dot(e2, qv) / det;
            const double w = 1.0 - u - v;
            if (u < -1e-9 || v < -1e-9 || w < -1e-9 || t <= 0.0) continue;
            hits.push_back({t, static_cast<int>(leaf), glm::normalize(glm::cross(e1, e2)), std::min({u, v, w})});
        }
    }
    BruteResult result;
    std::sort(hits.begin(), hits.end(), [](const BruteHit& x, const BruteHit& y) { return x.t < y.t; });
    for (std::size_t k = 0; k < hits.size(); ++k) {
        if (hits[k].edge < 1e-6) result.nearEdge = true;
        if (k > 0 && hits[k].t - hits[k - 1].t < 1e-6) result.nearEdge = true;
    }
    const std::size_t leaves = s.model.leafMeshes.size();
    auto membershipAfter = [&](std::size_t count) {  // after the first `count` hits
        std::vector<bool> in(leaves, false);
        for (std::size_t k = 0; k < count; ++k) in[static_cast<std::size_t>(hits[k].leaf)] = !in[static_cast<std::size_t>(hits[k].leaf)];
        return s.tree.root >= 0 && memberAt(s.tree, s.tree.root, in);
    };
    bool before = membershipAfter(0);
    for (std::size_t k = 0; k < hits.size(); ++k) {
        const bool after = membershipAfter(k + 1);
        if (after != before) {
            std::vector<bool> leafBefore(leaves, false);
            for (std::size_t m = 0; m < k; ++m) leafBefore[static_cast<std::size_t>(hits[m].leaf)] = !leafBefore[static_cast<std::size_t>(hits[m].leaf)];
            const bool leafEnters = !leafBefore[static_cast<std::size_t>(hits[k].leaf)];
            result.t = hits[k].t;
            result.leaf = hits[k].leaf;
            result.normal = leafEnters == after ? hits[k].normal : -hits[k].normal;
            return result;
        }
    }
    return result;
}

}  // namespace

// A busier scene (a stack of subtractions, an intersection, a union, a
// mirrored leaf), every pixel checked against the brute-force caster above,
// from an oblique camera in both projections.
TEST(RayCaster, WholeImagesAgreeWithBruteForce) {
    SceneBuilder s;
    const int slab = s.leaf(box({-2, -2, -0.6}, {2, 2, 0.6}));
    std::vector<int> cuts;
    for (int k = 0; k < 4; ++k) cuts.push_back(s.leaf(sphere(0.55, 12, {-1.5 + k, 0.3 * k - 0.5, 0.1 * k})));
    const int lens = s.intersect({s.leaf(sphere(1.0, 20, {0, 0, 0.8})), s.leaf(sphere(1.0, 20, {0, 0, 1.9}))});
    const int post = s.leaf(mirrored(box({0.5, 0.5, -1.5}, {1.0, 1.0, 2.5}), 1));
    std::vector<int> difference{slab};
    difference.insert(difference.end(), cuts.begin(), cuts.end());
    s.setRoot(s.unite({s.subtract(difference), lens, post}));

    int compared = 0, hit = 0;
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        Camera camera;
        camera.eye = {6.0, -7.0, 5.0};
        camera.center = {0.0, 0.0, 0.3};
        camera.width = 48;
        camera.height = 40;
        camera.fovDegrees = 35.0;
        camera.projection = projection;
        const ReferenceImage image = renderReference(s.tree, s.model, camera);
        for (int j = 0; j < camera.height; ++j) {
            for (int i = 0; i < camera.width; ++i) {
                const auto ray = camera.ray(i, j);
                const BruteResult expected = bruteForce(s, ray);
                if (expected.nearEdge) continue;
                const std::size_t k = static_cast<std::size_t>(j) * camera.width + i;
                ++compared;
                ASSERT_EQ(image.leaf[k], expected.leaf) << "pixel " << i << "," << j;
                if (expected.leaf < 0) {
                    EXPECT_EQ(image.depth[k], kInfF);
                    continue;
                }
                ++hit;
                const double depth = camera.viewDepth(ray.origin + expected.t * ray.direction);
                EXPECT_NEAR(image.depth[k], depth, 1e-5 * depth) << "pixel " << i << "," << j;
                expectNormal(image.normal[k], glm::vec3(expected.normal));
            }
        }
    }
    EXPECT_GT(compared, 2 * 48 * 40 * 9 / 10);
    EXPECT_GT(hit, compared / 4);
}

TEST(RayCaster, ThreadsDoNotChangeTheImageAndProgressReachesTheEnd) {
    SceneBuilder s;
    const int cube = s.leaf(box({-1, -1, -1}, {1, 1, 1}));
    const int ball = s.leaf(sphere(1.2, 24, {0.3, -0.2, 0.4}));
    s.setRoot(s.subtract({cube, ball}));
    Camera camera;
    camera.eye = {4.0, -5.0, 3.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = 37;
    camera.height = 23;
    const ReferenceScene scene(s.tree, s.model);
    ReferenceOptions one;
    one.threads = 1;
    int calls = 0, last = 0;
    one.progress = [&](int done, int total) {
        ++calls;
        EXPECT_EQ(total, 23);
        EXPECT_EQ(done, last + 1);
        last = done;
    };
    const ReferenceImage a = scene.render(camera, one);
    EXPECT_EQ(calls, 23);
    EXPECT_EQ(last, 23);
    ReferenceOptions many;
    many.threads = 5;
    const ReferenceImage b = scene.render(camera, many);
    ASSERT_EQ(a.depth.size(), b.depth.size());
    EXPECT_EQ(std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(a.normal.data(), b.normal.data(), a.normal.size() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(a.leaf, b.leaf);
    // trace() agrees with render() for a pixel.
    const auto ray = camera.ray(18, 11);
    const RayHit h = scene.trace(ray);
    const std::size_t k = 11u * 37u + 18u;
    EXPECT_EQ(h.leaf, a.leaf[k]);
    if (h.hit()) {
        EXPECT_EQ(static_cast<float>(camera.viewDepth(ray.origin + h.t * ray.direction)), a.depth[k]);
    }
}

// Rays from inside a closed leaf, aimed exactly at its vertices and edges,
// must always find the way out (an odd number of crossings after the start),
// and rays from outside aimed the same way must hit it or graze it, never
// start "inside": Embree's float traversal must not lose a triangle that the
// exact test claims.
TEST(RayCaster, RaysThroughVerticesAndEdgesKeepInsideAndOutsideApart) {
    const strata::mesh::Mesh meshes[] = {sphere(1.0, 16, {0.2, -0.1, 0.3}), box({-1, -2, -0.5}, {1, 2, 0.5}),
                                             sphere(3.0, 9)};
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int entered = 0, aimed = 0;
    for (const auto& mesh : meshes) {
        SceneBuilder s;
        s.setRoot(s.leaf(mesh));
        const ReferenceScene scene(s.tree, s.model);
        glm::dvec3 centroid{0.0};
        for (const auto& p : mesh.positions) centroid += p / static_cast<double>(mesh.positions.size());
        std::vector<glm::dvec3> targets = mesh.positions;
        for (const auto& t : mesh.triangles) targets.push_back((mesh.positions[t[0]] + mesh.positions[t[2]]) * 0.5);
        for (const glm::dvec3& target : targets) {
            ++aimed;
            const glm::dvec3 inside = centroid + 0.1 * glm::dvec3(unit(rng), unit(rng), unit(rng));
            const glm::dvec3 d = glm::normalize(target - inside);
            const RayHit out = scene.trace({inside, d});
            ASSERT_TRUE(out.hit()) << "from inside towards (" << target.x << ", " << target.y << ", " << target.z << ")";
            EXPECT_NEAR(out.t, glm::length(target - inside), 1e-9);
            EXPECT_GT(glm::dot(out.normal, d), 0.0);  // leaving: the outward normal points along the ray

            const glm::dvec3 outside = centroid + 20.0 * glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
            const glm::dvec3 e = glm::normalize(target - outside);
            const RayHit in = scene.trace({outside, e});
            if (!in.hit()) continue;  // a graze at the silhouette: a box's corners see many
            ++entered;
            EXPECT_LE(in.t, glm::length(target - outside) + 1e-9);
            EXPECT_LT(glm::dot(in.normal, e), 0.0);  // entering
        }
    }
    EXPECT_GT(entered, aimed / 2);
}
