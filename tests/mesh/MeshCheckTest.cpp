#include "strata/mesh/MeshCheck.h"

#include <gtest/gtest.h>

#include <utility>

#include "MeshTestUtil.h"
#include "strata/mesh/Primitives.h"

using namespace strata;
using namespace strata::mesh;
using strata::mesh::test::signedVolume;
using strata::mesh::test::surfaceArea;

namespace {

Mesh unitCube() { return tessellate(scene::Cube{{1, 1, 1}, false}); }

// The tetrahedron (0,0,0), (2,0,0), (0,2,0), (0,0,2), outward.
Mesh tetrahedron() {
    Mesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

}  // namespace

TEST(CheckMesh, ClosedOutwardMeshesPass) {
    for (const Mesh& m : {unitCube(), tetrahedron(), tessellate(scene::Sphere{1, {9, 12, 2}})}) {
        const MeshCheck c = checkMesh(m);
        EXPECT_TRUE(c.ok()) << c.describe();
        EXPECT_EQ(c.describe(), "");
    }
    EXPECT_TRUE(checkMesh(Mesh{}).ok());
}

TEST(CheckMesh, MissingFaceLeavesBoundaryEdges) {
    Mesh m = unitCube();
    m.triangles.pop_back();  // one triangle: its three edges lose their partner
    const MeshCheck c = checkMesh(m);
    EXPECT_EQ(c.boundaryEdges, 3u);
    EXPECT_EQ(c.nonManifoldEdges, 0u);
    EXPECT_EQ(c.misorientedEdges, 0u);
    EXPECT_FALSE(c.ok());
    EXPECT_EQ(c.describe(), "not closed: 3 boundary edges");
}

TEST(CheckMesh, FlippedFaceIsInconsistentlyOriented) {
    Mesh m = tetrahedron();
    std::swap(m.triangles[3][1], m.triangles[3][2]);
    const MeshCheck c = checkMesh(m);
    EXPECT_EQ(c.boundaryEdges, 0u);
    EXPECT_EQ(c.misorientedEdges, 3u);
    EXPECT_FALSE(c.inwardOriented);
    EXPECT_EQ(c.describe(), "inconsistently oriented: 3 edges");
}

TEST(CheckMesh, ThirdTriangleOnAnEdgeIsNonManifold) {
    Mesh m = tetrahedron();
    m.positions.push_back({1, -1, 1});
    m.triangles.push_back({0, 1, 4});  // a fin on edge 0-1
    const MeshCheck c = checkMesh(m);
    EXPECT_EQ(c.nonManifoldEdges, 1u);
    EXPECT_EQ(c.boundaryEdges, 2u);
    EXPECT_EQ(c.describe(), "not closed: 2 boundary edges; not manifold: 1 edge shared by more than two triangles");
}

TEST(CheckMesh, AllFlippedIsInwardOriented) {
    Mesh m = unitCube();
    for (auto& t : m.triangles) std::swap(t[0], t[1]);
    const MeshCheck c = checkMesh(m);
    EXPECT_EQ(c.boundaryEdges + c.nonManifoldEdges + c.misorientedEdges, 0u);
    EXPECT_TRUE(c.inwardOriented);
    EXPECT_EQ(c.describe(), "inward oriented (negative volume)");
}

TEST(CheckMesh, InwardNeedsAClosedConsistentMesh) {
    Mesh m = unitCube();
    for (auto& t : m.triangles) std::swap(t[0], t[1]);
    m.triangles.pop_back();
    EXPECT_FALSE(checkMesh(m).inwardOriented);
}

TEST(CheckMesh, JudgesTriangleSoupsByPosition) {
    // Every triangle of the cube on its own three vertices.
    const Mesh cube = unitCube();
    Mesh soup;
    for (const auto& t : cube.triangles) {
        const auto base = static_cast<uint32_t>(soup.positions.size());
        for (uint32_t v : t) soup.positions.push_back(cube.positions[v]);
        soup.triangles.push_back({base, base + 1, base + 2});
    }
    EXPECT_TRUE(checkMesh(soup).ok()) << checkMesh(soup).describe();
}

TEST(MergeCoincidentVertices, WeldsEqualPositionsIncludingSignedZero) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {-0.0, 0, -0.0}, {0, 1, 0}, {1, 0, 0}};
    m.triangles = {{0, 1, 3}, {2, 3, 4}};
    mergeCoincidentVertices(m);
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[0], glm::dvec3(0, 0, 0));
    EXPECT_EQ(m.positions[1], glm::dvec3(1, 0, 0));
    EXPECT_EQ(m.positions[2], glm::dvec3(0, 1, 0));
    EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 1}));
}

TEST(DropDegenerateTriangles, RemovesRepeatedVertexTrianglesAndUnusedVertices) {
    Mesh m = tetrahedron();
    m.positions.push_back({5, 5, 5});        // unused
    m.positions.push_back({0, 0, 0});        // a copy of vertex 0
    m.triangles.push_back({0, 5, 1});        // zero area once 5 is welded to 0
    m.triangles.push_back({2, 2, 3});
    dropDegenerateTriangles(m);
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 4u);
    EXPECT_TRUE(checkMesh(m).ok());
    EXPECT_DOUBLE_EQ(signedVolume(m), 8.0 / 6.0);
}

TEST(DropDegenerateTriangles, SplitsTheNeighbourOfACollinearSliver) {
    //  The tetrahedron's face (0,1,3) is split at M = (1,0,0), the midpoint of
    //  edge 0-1, and a zero-area sliver (0,1,M) closes the T-junction:
    //
    //    3
    //    |'.         face (0,2,1) below still uses edge 1->0 whole
    //    |  '.
    //    0--M--1     sliver 0->1->M->0 lies along the edge
    Mesh m = tetrahedron();
    m.positions.push_back({1, 0, 0});  // M = 4
    m.triangles = {{0, 2, 1}, {0, 4, 3}, {4, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 1, 4}};
    ASSERT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    const double area = surfaceArea(m);
    dropDegenerateTriangles(m);
    EXPECT_EQ(m.triangles.size(), 6u);  // sliver gone, the bottom split in two
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_DOUBLE_EQ(signedVolume(m), 8.0 / 6.0);
    EXPECT_DOUBLE_EQ(surfaceArea(m), area);
    for (const auto& t : m.triangles) {
        const glm::dvec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(glm::length(n), 0.0);
    }
}

TEST(DropDegenerateTriangles, KeepsTinyButRealTriangles) {
    Mesh m = tetrahedron();
    for (auto& p : m.positions) p *= 1e-200;  // cross products would underflow to 0
    dropDegenerateTriangles(m);
    EXPECT_EQ(m.triangles.size(), 4u);
}

TEST(DropDegenerateTriangles, KeepsThePositionsOrder) {
    Mesh m = tessellate(scene::Sphere{1, {8, 12, 2}});
    const Mesh before = m;
    dropDegenerateTriangles(m);
    EXPECT_EQ(m.positions, before.positions);
    EXPECT_EQ(m.triangles, before.triangles);
}
