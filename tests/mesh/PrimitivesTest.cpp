#include "strata/mesh/Primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "MeshTestUtil.h"
#include "strata/core/Error.h"
#include "strata/mesh/MeshCheck.h"

using namespace strata;
using namespace strata::mesh;
using strata::mesh::test::regularPolygonArea;
using strata::mesh::test::signedVolume;
using strata::mesh::test::surfaceArea;
using strata::mesh::test::triangleNormal;

namespace {

constexpr double kPi = 3.14159265358979323846;

scene::Fragments frag(double fn, double fa = 12.0, double fs = 2.0) { return {fn, fa, fs}; }

// OpenSCAD 2021.01's rule, written out again: $fa and $fs below 0.01 are
// clamped to 0.01; radii below 2^-20 give 3; $fn > 0 is truncated, at least 3.
int expectedFragments(double r, double fn, double fa, double fs) {
    fa = std::max(fa, 0.01);
    fs = std::max(fs, 0.01);
    if (r < std::ldexp(1.0, -20)) return 3;
    if (fn > 0) return std::max(static_cast<int>(std::floor(fn)), 3);
    const double byAngle = 360.0 / fa;
    const double byLength = r * 2 * kPi / fs;
    return static_cast<int>(std::ceil(std::max(std::min(byAngle, byLength), 5.0)));
}

// Triangles a polygon of n vertices becomes in OpenSCAD's preview.
int capTriangles(int n) { return n == 3 ? 1 : n == 4 ? 2 : n; }
int capCenters(int n) { return n > 4 ? 1 : 0; }

// Every triangle of a convex solid faces away from an interior point.
void expectFacesAwayFrom(const Mesh& m, const glm::dvec3& inside) {
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& t = m.triangles[i];
        const glm::dvec3 c = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0;
        const glm::dvec3 n = triangleNormal(m, i);
        ASSERT_GT(glm::length(n), 0.0) << "zero-area triangle " << i;
        ASSERT_GT(glm::dot(n, c - inside), 0.0) << "triangle " << i << " faces inward";
    }
}

}  // namespace

TEST(Fragments, HandComputedCases) {
    EXPECT_EQ(fragmentsFromR(10, frag(0, 12, 2)), 30);   // min(360/12, 2*pi*10/2 = 31.4) = 30
    EXPECT_EQ(fragmentsFromR(1, frag(0)), 5);            // 2*pi/2 = 3.14, at least 5
    EXPECT_EQ(fragmentsFromR(5, frag(0)), 16);           // ceil(15.7)
    EXPECT_EQ(fragmentsFromR(1, frag(2.7)), 3);          // $fn below 3 gives 3
    EXPECT_EQ(fragmentsFromR(1, frag(7.9)), 7);          // $fn is truncated
    EXPECT_EQ(fragmentsFromR(1, frag(100)), 100);
    EXPECT_EQ(fragmentsFromR(1e-7, frag(100)), 3);       // below 2^-20 always 3
    EXPECT_EQ(fragmentsFromR(1, frag(0, 1, 0.1)), 63);   // ceil(62.8)
    EXPECT_EQ(fragmentsFromR(1e6, frag(0, 0.001, 2)), 36000);  // $fa clamped to 0.01
    EXPECT_EQ(fragmentsFromR(1, frag(0, 12, 0)), 30);    // $fs clamped to 0.01: min(30, 628)
    EXPECT_EQ(fragmentsFromR(1, frag(-5)), 5);           // $fn <= 0 is ignored
    EXPECT_EQ(fragmentsFromR(1, frag(std::nan(""))), 3);
    EXPECT_EQ(fragmentsFromR(1, frag(INFINITY)), 3);
}

TEST(Fragments, MatchOpenScadRuleOverAGrid) {
    for (double r : {1e-7, 1e-6, 0.5, 1.0, 3.0, 10.0, 47.0, 100.0, 1000.0})
        for (double fn : {0.0, 2.7, 3.0, 7.9, 36.0})
            for (double fa : {12.0, 5.0, 1.0, 0.001})
                for (double fs : {2.0, 0.5, 0.1, 0.0}) {
                    EXPECT_EQ(fragmentsFromR(r, frag(fn, fa, fs)), expectedFragments(r, fn, fa, fs))
                        << "r=" << r << " fn=" << fn << " fa=" << fa << " fs=" << fs;
                }
}

TEST(Cube, HasEightCornersAndTwelveOutwardTriangles) {
    const Mesh m = tessellate(scene::Cube{{2, 3, 4}, false});
    ASSERT_EQ(m.positions.size(), 8u);
    ASSERT_EQ(m.triangles.size(), 12u);
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_DOUBLE_EQ(signedVolume(m), 24.0);
    EXPECT_DOUBLE_EQ(surfaceArea(m), 2 * (6 + 8 + 12));
    expectFacesAwayFrom(m, {1, 1.5, 2});
    const Bounds b = boundsOf(m);
    EXPECT_EQ(b.min, glm::dvec3(0, 0, 0));
    EXPECT_EQ(b.max, glm::dvec3(2, 3, 4));
}

TEST(Cube, CenteredIsSymmetricAboutTheOrigin) {
    const Mesh m = tessellate(scene::Cube{{2, 3, 4}, true});
    const Bounds b = boundsOf(m);
    EXPECT_EQ(b.min, glm::dvec3(-1, -1.5, -2));
    EXPECT_EQ(b.max, glm::dvec3(1, 1.5, 2));
    EXPECT_DOUBLE_EQ(signedVolume(m), 24.0);
    expectFacesAwayFrom(m, {0, 0, 0});
}

TEST(Cube, NonPositiveSizeIsEmpty) {
    for (glm::dvec3 s : {glm::dvec3(0, 1, 1), glm::dvec3(1, -1, 1), glm::dvec3(1, 1, 0), glm::dvec3(INFINITY, 1, 1)}) {
        const Mesh m = tessellate(scene::Cube{s, false});
        EXPECT_TRUE(m.positions.empty());
        EXPECT_TRUE(m.triangles.empty());
    }
}

TEST(Sphere, VertexAndTriangleCountsFollowRings) {
    for (int n = 3; n <= 40; ++n) {
        const Mesh m = tessellate(scene::Sphere{2.0, frag(n)});
        const int rings = (n + 1) / 2;
        EXPECT_EQ(m.positions.size(), std::size_t(n * rings + 2 * capCenters(n))) << "n=" << n;
        EXPECT_EQ(m.triangles.size(), std::size_t(2 * capTriangles(n) + 2 * n * (rings - 1))) << "n=" << n;
    }
}

TEST(Sphere, RingVerticesSitWhereOpenScadPutsThem) {
    for (double r : {0.5, 1.0, 7.25})
        for (int n : {3, 4, 5, 6, 8, 12, 13, 30}) {
            const Mesh m = tessellate(scene::Sphere{r, frag(n)});
            const int rings = (n + 1) / 2;
            for (int i = 0; i < rings; ++i) {
                const double phi = kPi * (i + 0.5) / rings;
                for (int k = 0; k < n; ++k) {
                    const double theta = 2 * kPi * k / n;
                    const glm::dvec3 expected(r * std::sin(phi) * std::cos(theta), r * std::sin(phi) * std::sin(theta),
                                              r * std::cos(phi));
                    const glm::dvec3 p = m.positions[std::size_t(i * n + k)];
                    EXPECT_NEAR(p.x, expected.x, 1e-12 * r) << "n=" << n << " ring " << i << " k=" << k;
                    EXPECT_NEAR(p.y, expected.y, 1e-12 * r);
                    EXPECT_NEAR(p.z, expected.z, 1e-12 * r);
                }
            }
        }
}

TEST(Sphere, SpecialAnglesAreExact) {
    // $fn = 12: rings = 6 at polar angles 15, 45, 75, 105, 135, 165 degrees;
    // vertices every 30 degrees.
    const double r = 3.0;
    const Mesh m = tessellate(scene::Sphere{r, frag(12)});
    const double s45 = 0.70710678118654752440;  // sin 45 as OpenSCAD's table has it
    const double ringR = r * s45;               // ring 1, at 45 degrees
    const double z = r * s45;
    auto vertex = [&](int ring, int k) { return m.positions[std::size_t(ring * 12 + k)]; };
    EXPECT_EQ(vertex(1, 0), glm::dvec3(ringR, 0.0, z));
    EXPECT_EQ(vertex(1, 3), glm::dvec3(0.0, ringR, z));  // 90 degrees: x exactly 0
    EXPECT_EQ(vertex(1, 6), glm::dvec3(-ringR, 0.0, z));
    EXPECT_EQ(vertex(1, 9), glm::dvec3(0.0, -ringR, z));
    EXPECT_EQ(vertex(1, 1).y, ringR * 0.5);  // sin 30 = 0.5 exactly
    EXPECT_EQ(vertex(1, 2).x, ringR * 0.5);  // cos 60 = 0.5 exactly
    EXPECT_EQ(vertex(4, 3), glm::dvec3(0.0, ringR, -z));  // 135 degrees: cos = -sin 45

    // $fn = 6: rings = 3 at 30, 90, 150 degrees; the middle ring is the equator.
    const Mesh six = tessellate(scene::Sphere{2.0, frag(6)});
    EXPECT_EQ(six.positions[6], glm::dvec3(2.0, 0.0, 0.0));
    EXPECT_EQ(six.positions[0].z, 2.0 * 0.86602540378443859659);
    EXPECT_EQ(six.positions[0].x, 2.0 * 0.5);
    EXPECT_EQ(six.positions[12].z, -2.0 * 0.86602540378443859659);
}

TEST(Sphere, IsClosedOutwardAndHasThePolygonalVolume) {
    for (double r : {0.5, 1.0, 10.0})
        for (int n : {3, 4, 5, 6, 7, 12, 31, 64}) {
            const Mesh m = tessellate(scene::Sphere{r, frag(n)});
            EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
            expectFacesAwayFrom(m, {0, 0, 0});
            // A stack of frustums between consecutive rings; the band faces are
            // planar trapezoids because the rings' vertices are aligned.
            const int rings = (n + 1) / 2;
            double volume = 0.0;
            for (int i = 0; i + 1 < rings; ++i) {
                const double phi0 = kPi * (i + 0.5) / rings, phi1 = kPi * (i + 1.5) / rings;
                const double a0 = regularPolygonArea(n, r * std::sin(phi0));
                const double a1 = regularPolygonArea(n, r * std::sin(phi1));
                const double h = r * (std::cos(phi0) - std::cos(phi1));
                volume += h / 3.0 * (a0 + a1 + std::sqrt(a0 * a1));
            }
            EXPECT_NEAR(signedVolume(m), volume, 1e-9 * r * r * r) << "n=" << n;
        }
}

TEST(Sphere, DefaultsGiveOpenScadsFiveFragmentSphere) {
    const Mesh m = tessellate(scene::Sphere{1.0, {}});
    EXPECT_EQ(m.positions.size(), 5u * 3u + 2u);  // 5 fragments, 3 rings, two cap centres
}

TEST(Sphere, TinyRadiusStillMakesAClosedSolid) {
    const Mesh m = tessellate(scene::Sphere{1e-7, frag(100)});
    EXPECT_EQ(m.positions.size(), 6u);  // 3 fragments, 2 rings
    EXPECT_EQ(m.triangles.size(), 8u);
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_GT(signedVolume(m), 0.0);
}

TEST(Sphere, NonPositiveRadiusIsEmpty) {
    EXPECT_TRUE(tessellate(scene::Sphere{0.0, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Sphere{-1.0, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Sphere{INFINITY, {}}).triangles.empty());
}

TEST(Cylinder, CountsAndVolume) {
    for (int n : {3, 4, 5, 6, 17, 30})
        for (double h : {0.5, 3.0}) {
            const Mesh m = tessellate(scene::Cylinder{h, 2.0, 2.0, false, frag(n)});
            EXPECT_EQ(m.positions.size(), std::size_t(2 * n + 2 * capCenters(n)));
            EXPECT_EQ(m.triangles.size(), std::size_t(2 * n + 2 * capTriangles(n)));
            EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
            EXPECT_NEAR(signedVolume(m), regularPolygonArea(n, 2.0) * h, 1e-12 * h);
            expectFacesAwayFrom(m, {0, 0, h / 2});
        }
}

TEST(Cylinder, VerticesSitOnTheCircles) {
    const double r1 = 3.0, r2 = 1.5, h = 2.0;
    const int n = 12;
    const Mesh m = tessellate(scene::Cylinder{h, r1, r2, true, frag(n)});
    for (int k = 0; k < n; ++k) {
        const double t = 2 * kPi * k / n;
        const glm::dvec3 bottom = m.positions[std::size_t(k)];
        const glm::dvec3 top = m.positions[std::size_t(n + k)];
        EXPECT_NEAR(bottom.x, r1 * std::cos(t), 1e-14);
        EXPECT_NEAR(bottom.y, r1 * std::sin(t), 1e-14);
        EXPECT_EQ(bottom.z, -1.0);
        EXPECT_NEAR(top.x, r2 * std::cos(t), 1e-14);
        EXPECT_NEAR(top.y, r2 * std::sin(t), 1e-14);
        EXPECT_EQ(top.z, 1.0);
    }
    // Special angles are exact: 90 degrees is (0, r), 30 has y = r/2, 180 is (-r, 0).
    EXPECT_EQ(m.positions[3], glm::dvec3(0.0, r1, -1.0));
    EXPECT_EQ(m.positions[1].y, r1 * 0.5);
    EXPECT_EQ(m.positions[6], glm::dvec3(-r1, 0.0, -1.0));
    EXPECT_EQ(m.positions[n + 9], glm::dvec3(0.0, -r2, 1.0));
    EXPECT_EQ(m.positions[1].x, r1 * 0.86602540378443859659);
}

TEST(Cylinder, FragmentsComeFromTheLargerRadius) {
    const Mesh m = tessellate(scene::Cylinder{1.0, 1.0, 10.0, false, {}});  // r=10 defaults: 30
    EXPECT_EQ(m.positions.size(), 2u * 30u + 2u);
}

TEST(Cylinder, ConeHasOneApexVertex) {
    for (int n : {3, 4, 5, 30}) {
        const double h = 4.0, r = 2.0;
        const Mesh up = tessellate(scene::Cylinder{h, r, 0.0, false, frag(n)});
        EXPECT_EQ(up.positions.size(), std::size_t(n + 1 + capCenters(n)));
        EXPECT_EQ(up.triangles.size(), std::size_t(n + capTriangles(n)));
        EXPECT_EQ(std::count(up.positions.begin(), up.positions.end(), glm::dvec3(0, 0, h)), 1);
        EXPECT_TRUE(checkMesh(up).ok()) << checkMesh(up).describe();
        EXPECT_NEAR(signedVolume(up), regularPolygonArea(n, r) * h / 3, 1e-12);
        expectFacesAwayFrom(up, {0, 0, h / 4});

        const Mesh down = tessellate(scene::Cylinder{h, 0.0, r, true, frag(n)});
        EXPECT_EQ(std::count(down.positions.begin(), down.positions.end(), glm::dvec3(0, 0, -h / 2)), 1);
        EXPECT_TRUE(checkMesh(down).ok()) << checkMesh(down).describe();
        EXPECT_NEAR(signedVolume(down), regularPolygonArea(n, r) * h / 3, 1e-12);
        expectFacesAwayFrom(down, {0, 0, h / 4});
    }
}

TEST(Cylinder, FrustumHasTheFrustumVolume) {
    const int n = 9;
    const double h = 2.0, r1 = 1.0, r2 = 3.0;
    const Mesh m = tessellate(scene::Cylinder{h, r1, r2, false, frag(n)});
    EXPECT_EQ(m.triangles.size(), std::size_t(2 * n + 2 * n));
    const double a1 = regularPolygonArea(n, r1), a2 = regularPolygonArea(n, r2);
    EXPECT_NEAR(signedVolume(m), h / 3 * (a1 + a2 + std::sqrt(a1 * a2)), 1e-12);
    EXPECT_TRUE(checkMesh(m).ok());
    expectFacesAwayFrom(m, {0, 0, 1});
}

TEST(Cylinder, DegenerateIsEmpty) {
    EXPECT_TRUE(tessellate(scene::Cylinder{0.0, 1, 1, false, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Cylinder{-1.0, 1, 1, false, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Cylinder{1.0, 0, 0, false, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Cylinder{1.0, -1, 1, false, {}}).triangles.empty());
    EXPECT_TRUE(tessellate(scene::Cylinder{INFINITY, 1, 1, false, {}}).triangles.empty());
}

TEST(Primitives, AbsurdFragmentCountThrowsInsteadOfExhaustingMemory) {
    EXPECT_THROW(tessellate(scene::Sphere{1.0, frag(1e9)}), Error);
    EXPECT_THROW(tessellate(scene::Cylinder{1.0, 1.0, 1.0, false, frag(1e12)}), Error);
}

namespace {

// A prism over a 2D outline given counter-clockwise seen from +Z, with faces
// listed as OpenSCAD wants them: clockwise seen from outside.
scene::Polyhedron prism(const std::vector<glm::dvec2>& outline, double h) {
    scene::Polyhedron p;
    const int n = static_cast<int>(outline.size());
    for (const auto& q : outline) p.points.emplace_back(q.x, q.y, 0.0);
    for (const auto& q : outline) p.points.emplace_back(q.x, q.y, h);
    std::vector<int> bottom, top;
    for (int i = 0; i < n; ++i) bottom.push_back(i);          // clockwise seen from below
    for (int i = n - 1; i >= 0; --i) top.push_back(n + i);    // clockwise seen from above
    p.faces = {bottom, top};
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        p.faces.push_back({n + i, n + j, j, i});
    }
    return p;
}

double polygonArea(const std::vector<glm::dvec2>& o) {
    double a = 0.0;
    for (std::size_t i = 0; i < o.size(); ++i) {
        const auto& p = o[i];
        const auto& q = o[(i + 1) % o.size()];
        a += p.x * q.y - q.x * p.y;
    }
    return a / 2;
}

double perimeter(const std::vector<glm::dvec2>& o) {
    double l = 0.0;
    for (std::size_t i = 0; i < o.size(); ++i) l += glm::length(o[(i + 1) % o.size()] - o[i]);
    return l;
}

}  // namespace

TEST(Polyhedron, NonConvexFacesTriangulateToTheirArea) {
    const std::vector<std::vector<glm::dvec2>> outlines = {
        {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},                // L hexagon, area 3
        {{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}},                        // arrow pentagon, area 10
        {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}},  // U octagon, area 7
        {{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}},                            // dart quad, area 1
    };
    const std::vector<double> areas = {3, 10, 7, 1};
    for (std::size_t s = 0; s < outlines.size(); ++s) {
        const auto& o = outlines[s];
        ASSERT_DOUBLE_EQ(polygonArea(o), areas[s]);
        const double h = 1.5;
        const Mesh m = tessellate(prism(o, h));
        EXPECT_TRUE(checkMesh(m).ok()) << s << ": " << checkMesh(m).describe();
        EXPECT_NEAR(signedVolume(m), areas[s] * h, 1e-12) << s;
        EXPECT_NEAR(surfaceArea(m), 2 * areas[s] + perimeter(o) * h, 1e-12) << s;
        // The cap triangles all face out: +Z on top, -Z below.
        for (std::size_t i = 0; i < m.triangles.size(); ++i) {
            const auto& t = m.triangles[i];
            const double z = m.positions[t[0]].z;
            if (z == m.positions[t[1]].z && z == m.positions[t[2]].z) {
                EXPECT_GT(triangleNormal(m, i).z * (z > 0 ? 1 : -1), 0.0) << s << " triangle " << i;
            }
        }
    }
}

TEST(Polyhedron, RandomStarShapedFacesTriangulateExactly) {
    // Star-shaped outlines (random radius per angle) are simple but very
    // non-convex; every cap triangle must face out and the caps must add up
    // to the shoelace area.
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> radius(0.2, 2.0);
    for (int trial = 0; trial < 50; ++trial) {
        const int n = 5 + trial * 3;
        std::vector<glm::dvec2> outline;
        for (int k = 0; k < n; ++k) {
            const double a = 2 * kPi * k / n, r = radius(rng);
            outline.emplace_back(r * std::cos(a), r * std::sin(a));
        }
        const double area = polygonArea(outline);
        const Mesh m = tessellate(prism(outline, 1.0));
        EXPECT_TRUE(checkMesh(m).ok()) << "n=" << n << ": " << checkMesh(m).describe();
        EXPECT_NEAR(signedVolume(m), area, 1e-12 * n) << "n=" << n;
        double top = 0.0;
        for (std::size_t i = 0; i < m.triangles.size(); ++i) {
            const auto& t = m.triangles[i];
            if (m.positions[t[0]].z == 1.0 && m.positions[t[1]].z == 1.0 && m.positions[t[2]].z == 1.0) {
                const double twiceArea = triangleNormal(m, i).z;
                EXPECT_GT(twiceArea, 0.0) << "n=" << n << " triangle " << i;
                top += twiceArea / 2;
            }
        }
        EXPECT_NEAR(top, area, 1e-12 * n) << "n=" << n;
    }
}

TEST(Polyhedron, CollinearPointsOnAFaceMakeNoSlivers) {
    // A box whose x = 0 edge at y = 0 ... the bottom front edge has a midpoint
    // shared by the bottom and the front face.
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}};
    p.faces = {
        {0, 8, 1, 2, 3},  // bottom, clockwise from below
        {4, 7, 6, 5},     // top
        {0, 4, 5, 1, 8},  // front (y = 0)
        {1, 5, 6, 2},     // x = 2
        {2, 6, 7, 3},     // y = 2
        {3, 7, 4, 0},     // x = 0
    };
    const Mesh m = tessellate(p);
    for (std::size_t i = 0; i < m.triangles.size(); ++i) EXPECT_GT(glm::length(triangleNormal(m, i)), 0.0) << i;
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_NEAR(signedVolume(m), 8.0, 1e-12);
}

TEST(Polyhedron, OutOfRangeIndexThrows) {
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.faces = {{0, 1, 3}};
    EXPECT_THROW(tessellate(p), Error);
    p.faces = {{0, -1, 2}};
    EXPECT_THROW(tessellate(p), Error);
}

TEST(Polyhedron, DegenerateFacesGiveNoTriangles) {
    scene::Polyhedron p;
    p.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.faces = {{}, {0}, {0, 1}, {0, 1, 1}, {2, 2, 2, 2}};
    EXPECT_TRUE(tessellate(p).triangles.empty());
}
