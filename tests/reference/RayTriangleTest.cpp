// The exact crossing test: right answers inside triangles, and exactly one
// claim where a ray passes through an edge or a vertex that triangles share.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "TestMeshes.h"
#include "strata/reference/RayTriangle.h"

using strata::reference::crossTriangle;
using strata::reference::RayFrame;
using strata::reference::TriangleCrossing;
using strata::camera::Ray;

namespace {

struct Claim {
    double t;
    bool entering;
};

std::vector<Claim> claims(const strata::mesh::Mesh& mesh, const Ray& ray) {
    const RayFrame frame(ray);
    std::vector<Claim> out;
    for (const auto& tri : mesh.triangles) {
        if (auto c = crossTriangle(frame, mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]])) {
            out.push_back({c->t, c->entering});
        }
    }
    std::sort(out.begin(), out.end(), [](const Claim& a, const Claim& b) { return a.t < b.t; });
    return out;
}

}  // namespace

TEST(RayTriangle, CrossesTheInsideWithDistanceAndFacing) {
    // Counter-clockwise seen from +Z: the outward normal is +Z.
    const glm::dvec3 a{-1, -1, 0}, b{1, -1, 0}, c{0, 1, 0};
    const auto down = crossTriangle(RayFrame({{0.1, 0.2, 5.0}, {0, 0, -1}}), a, b, c);
    ASSERT_TRUE(down.has_value());
    EXPECT_DOUBLE_EQ(down->t, 5.0);
    EXPECT_TRUE(down->entering);  // against the normal: into the solid
    const auto up = crossTriangle(RayFrame({{0.1, 0.2, -3.0}, {0, 0, 1}}), a, b, c);
    ASSERT_TRUE(up.has_value());
    EXPECT_DOUBLE_EQ(up->t, 3.0);
    EXPECT_FALSE(up->entering);
    // A slanted ray: from (0,0,4) along (0.6, 0, -0.8) meets z = 0 at x = 3: outside.
    EXPECT_FALSE(crossTriangle(RayFrame({{0, 0, 4}, {0.6, 0, -0.8}}), a, b, c).has_value());
    // From (-0.3, 0, 4) it meets z = 0 at (0.3*..): x = -0.3 + 3 = 2.7: outside; from (-2.7, 0, 4) at x = 0.3.
    const auto slanted = crossTriangle(RayFrame({{-2.7, 0, 4}, {0.6, 0, -0.8}}), a, b, c);
    ASSERT_TRUE(slanted.has_value());
    EXPECT_NEAR(slanted->t, 5.0, 1e-12);
    // The whole line counts: behind the origin gives a negative t.
    const auto behind = crossTriangle(RayFrame({{0, 0, -2}, {0, 0, -1}}), a, b, c);
    ASSERT_TRUE(behind.has_value());
    EXPECT_DOUBLE_EQ(behind->t, -2.0);
}

TEST(RayTriangle, EdgeOnTrianglesAreNeverCrossed) {
    EXPECT_FALSE(crossTriangle(RayFrame({{0, -5, 0}, {0, 1, 0}}), {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}).has_value());
}

// A flat grid of triangles: rays through the grid's shared edges and vertices,
// straight and slanted, must be claimed by exactly one triangle.
TEST(RayTriangle, SharedEdgesAndVerticesAreClaimedOnce) {
    strata::mesh::Mesh grid;
    const int n = 6;
    for (int y = 0; y <= n; ++y) {
        for (int x = 0; x <= n; ++x) grid.positions.push_back({x * 0.5, y * 0.5, 0.0});
    }
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const uint32_t v = static_cast<uint32_t>(y * (n + 1) + x);
            const uint32_t w = static_cast<uint32_t>(n + 1);
            if ((x + y) % 2 == 0) {
                grid.triangles.push_back({v, v + 1, v + w + 1});
                grid.triangles.push_back({v, v + w + 1, v + w});
            } else {
                grid.triangles.push_back({v, v + 1, v + w});
                grid.triangles.push_back({v + 1, v + w + 1, v + w});
            }
        }
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int tested = 0;
    for (int y = 1; y < n; ++y) {
        for (int x = 1; x < n; ++x) {
            const glm::dvec3 vertex{x * 0.5, y * 0.5, 0.0};
            const glm::dvec3 edgeMid{x * 0.5 + 0.25, y * 0.5, 0.0};            // a horizontal edge
            const glm::dvec3 diagonal{x * 0.5 + 0.2, y * 0.5 + 0.2, 0.0};       // on a diagonal or near one
            for (const glm::dvec3& target : {vertex, edgeMid, diagonal}) {
                for (int k = 0; k < 8; ++k) {
                    const glm::dvec3 from = target + glm::dvec3(3.0 * unit(rng), 3.0 * unit(rng), 4.0 + unit(rng));
                    const Ray ray{from, glm::normalize(target - from)};
                    const auto hits = claims(grid, ray);
                    ASSERT_EQ(hits.size(), 1u) << "ray towards (" << target.x << ", " << target.y << ")";
                    EXPECT_TRUE(hits[0].entering);
                    EXPECT_NEAR(hits[0].t, glm::length(target - from), 1e-12);
                    ++tested;
                }
                // Straight down, where the projection is exact.
                const auto straight = claims(grid, Ray{target + glm::dvec3(0, 0, 2), {0, 0, -1}});
                ASSERT_EQ(straight.size(), 1u);
            }
        }
    }
    EXPECT_GT(tested, 500);
}

// A roof: two faces meeting at a ridge along X. A ray across the ridge
// crosses once; a ray that grazes it (stays outside on both sides) is
// claimed by both faces or by none, never by one.
TEST(RayTriangle, RidgeIsCrossedOnceAndGrazedEvenly) {
    strata::mesh::Mesh roof;
    roof.positions = {{-1, 0, 0}, {1, 0, 0}, {0, 1, -1}, {0, -1, -1}};
    roof.triangles = {{0, 1, 2}, {1, 0, 3}};  // the shared edge runs both ways: consistently oriented
    // Their outward normals point up: (0,1,1) and (0,-1,1), normalized.
    for (double x : {-0.5, 0.0, 0.25, 0.7}) {
        const glm::dvec3 ridge{x, 0.0, 0.0};
        // Down through the ridge: the ray goes in.
        for (const glm::dvec3& dir : {glm::dvec3(0, 0, -1), glm::dvec3(0.1, 0.3, -1), glm::dvec3(-0.2, -0.5, -1)}) {
            const glm::dvec3 d = glm::normalize(dir);
            const auto hits = claims(roof, Ray{ridge - 3.0 * d, d});
            ASSERT_EQ(hits.size(), 1u);
            EXPECT_TRUE(hits[0].entering);
        }
        // Grazing: |dz| < |dy| keeps the line above both faces.
        for (const glm::dvec3& dir : {glm::dvec3(0, 1, 0.3), glm::dvec3(0.2, -1, -0.5), glm::dvec3(0, 1, 0)}) {
            const glm::dvec3 d = glm::normalize(dir);
            const auto hits = claims(roof, Ray{ridge - 3.0 * d, d});
            ASSERT_TRUE(hits.size() == 0 || hits.size() == 2) << hits.size();
            if (hits.size() == 2) {
                EXPECT_NE(hits[0].entering, hits[1].entering);
            }
        }
    }
}

// Closed convex meshes: any line meets them in one segment, so every ray is
// claimed twice (in, then out) or not at all, also when it is aimed exactly at
// vertices and edges, where tolerance-based tests drop or double crossings.
TEST(RayTriangle, ConvexMeshesAreEnteredOnceAndLeftOnce) {
    using namespace strata::reference::test;
    const strata::mesh::Mesh meshes[] = {box({-1, -2, -0.5}, {1, 2, 0.5}), sphere(1.5, 16), sphere(2.0, 7, {1, 1, 1})};
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int crossed = 0;
    for (const auto& mesh : meshes) {
        ASSERT_GT(signedVolume(mesh), 0.0);  // the helper's meshes face outward
        std::vector<glm::dvec3> targets = mesh.positions;
        for (const auto& t : mesh.triangles) {
            targets.push_back((mesh.positions[t[0]] + mesh.positions[t[1]]) * 0.5);
            targets.push_back((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0);
        }
        for (const glm::dvec3& target : targets) {
            for (int k = 0; k < 4; ++k) {
                const glm::dvec3 from = 10.0 * glm::dvec3(unit(rng), unit(rng), unit(rng));
                const Ray ray{from, glm::normalize(target - from)};
                const auto hits = claims(mesh, ray);
                ASSERT_TRUE(hits.size() == 0 || hits.size() == 2)
                    << hits.size() << " claims towards (" << target.x << ", " << target.y << ", " << target.z << ")";
                if (hits.size() == 2) {
                    // In, then out; a graze (both claims at one point) may come in either order.
                    if (hits[1].t - hits[0].t > 1e-9) {
                        EXPECT_TRUE(hits[0].entering) << hits[0].t << " " << hits[1].t;
                        EXPECT_FALSE(hits[1].entering);
                    }
                    ++crossed;
                }
            }
        }
    }
    EXPECT_GT(crossed, 1000);
}
