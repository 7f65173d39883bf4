#include "strata/mesh/Mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "MeshTestUtil.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/mesh/Primitives.h"

using namespace strata;
using namespace strata::mesh;
using strata::mesh::test::signedVolume;

TEST(Bounds, StartsEmptyAndGrowsWithPoints) {
    Bounds b;
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(b.diagonal(), 0.0);
    b.extend(glm::dvec3(1, 2, 3));
    EXPECT_FALSE(b.empty());
    EXPECT_EQ(b.diagonal(), 0.0);
    b.extend(glm::dvec3(-2, 6, 3));
    EXPECT_EQ(b.min, glm::dvec3(-2, 2, 3));
    EXPECT_EQ(b.max, glm::dvec3(1, 6, 3));
    EXPECT_EQ(b.center(), glm::dvec3(-0.5, 4, 3));
    EXPECT_DOUBLE_EQ(b.diagonal(), 5.0);  // 3-4-5

    Bounds other;
    b.extend(other);  // empty changes nothing
    EXPECT_EQ(b.min, glm::dvec3(-2, 2, 3));
    other.extend(glm::dvec3(0, 0, 10));
    b.extend(other);
    EXPECT_EQ(b.min, glm::dvec3(-2, 0, 3));
    EXPECT_EQ(b.max, glm::dvec3(1, 6, 10));
}

TEST(Bounds, OfAMeshCoversItsPositions) {
    const Mesh m = tessellate(scene::Cube{{1, 2, 3}, true});
    const Bounds b = boundsOf(m);
    EXPECT_EQ(b.min, glm::dvec3(-0.5, -1, -1.5));
    EXPECT_EQ(b.max, glm::dvec3(0.5, 1, 1.5));
    EXPECT_TRUE(boundsOf(Mesh{}).empty());
}

TEST(Transformed, MovesPointsAsColumnVectors) {
    const Mesh cube = tessellate(scene::Cube{{1, 1, 1}, false});
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(10, 20, 30));
    t = glm::scale(t, glm::dvec3(2, 3, 4));  // scale first, then translate
    const Mesh m = transformed(cube, t);
    const Bounds b = boundsOf(m);
    EXPECT_EQ(b.min, glm::dvec3(10, 20, 30));
    EXPECT_EQ(b.max, glm::dvec3(12, 23, 34));
    EXPECT_EQ(m.triangles, cube.triangles);
    EXPECT_DOUBLE_EQ(signedVolume(m), 24.0);
}

TEST(Transformed, RotationKeepsVolumeAndOrientation) {
    const Mesh s = tessellate(scene::Sphere{2.0, {16, 12, 2}});
    const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(glm::dvec3(1, 2, 3)));
    const Mesh m = transformed(s, r);
    EXPECT_NEAR(signedVolume(m), signedVolume(s), 1e-12);
    EXPECT_EQ(m.triangles, s.triangles);
}

TEST(Transformed, MirrorReversesTrianglesSoTheMeshStaysOutward) {
    const Mesh cyl = tessellate(scene::Cylinder{2.0, 1.0, 0.5, false, {7, 12, 2}});
    for (glm::dvec3 s : {glm::dvec3(-1, 1, 1), glm::dvec3(1, -2, 1), glm::dvec3(-1, -1, -1)}) {
        const Mesh m = transformed(cyl, glm::scale(glm::dmat4(1.0), s));
        EXPECT_GT(signedVolume(m), 0.0);
        EXPECT_NEAR(signedVolume(m), signedVolume(cyl) * std::abs(s.x * s.y * s.z), 1e-12);
        EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
        EXPECT_EQ(m.triangles[0][1], cyl.triangles[0][2]);
        EXPECT_EQ(m.triangles[0][2], cyl.triangles[0][1]);
    }
}

TEST(Transformed, IgnoresTheProjectiveRow) {
    // OpenSCAD's multmatrix is affine: a bottom row other than (0,0,0,1) is ignored.
    glm::dmat4 t(1.0);
    t[0][3] = 5.0;  // column 0, row 3
    t[3][3] = 2.0;
    Mesh m;
    m.positions = {{1, 2, 3}};
    EXPECT_EQ(transformed(m, t).positions[0], glm::dvec3(1, 2, 3));
}

TEST(CanonicalOrder, OneOrderForTheSameTrianglesHoweverTheyCome) {
    // A sphere's mesh, and the same mesh with its points renumbered and its
    // triangles shuffled and turned: both give the same points and
    // triangles, in order of position, with every triangle's orientation
    // and the volume kept.
    const Mesh sphere = tessellate(scene::Sphere{2.0, {14, 12, 2}});
    Mesh shuffled;
    std::vector<uint32_t> renumber(sphere.positions.size());
    for (std::size_t i = 0; i < renumber.size(); ++i) renumber[i] = static_cast<uint32_t>((i * 7 + 3) % renumber.size());
    ASSERT_EQ(std::gcd(std::size_t(7), renumber.size()), 1u);
    shuffled.positions.resize(sphere.positions.size());
    for (std::size_t i = 0; i < renumber.size(); ++i) shuffled.positions[renumber[i]] = sphere.positions[i];
    for (std::size_t t = sphere.triangles.size(); t-- > 0;) {
        std::array<uint32_t, 3> tri = sphere.triangles[t];
        for (uint32_t& v : tri) v = renumber[v];
        std::rotate(tri.begin(), tri.begin() + static_cast<long>(t % 3), tri.end());
        shuffled.triangles.push_back(tri);
    }
    Mesh a = sphere, b = shuffled;
    canonicalOrder(a);
    canonicalOrder(b);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.triangles, b.triangles);
    for (std::size_t i = 1; i < a.positions.size(); ++i) {
        const glm::dvec3 p = a.positions[i - 1], q = a.positions[i];
        EXPECT_TRUE(p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z <= q.z) << i;
    }
    for (const std::array<uint32_t, 3>& t : a.triangles) EXPECT_LT(t[0], std::min(t[1], t[2]));
    EXPECT_TRUE(std::is_sorted(a.triangles.begin(), a.triangles.end()));
    EXPECT_NEAR(signedVolume(a), signedVolume(sphere), 1e-12);
    EXPECT_TRUE(checkMesh(a).ok()) << checkMesh(a).describe();
}
