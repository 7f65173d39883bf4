// The join of coplanar faces (engine/exact/CoplanarFaces.h) on many regions
// at once, which it splits over threads: against the closed form of cubes
// whose faces were cut into four triangles around their centres.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "../mesh/MeshTestUtil.h"
#include "CoplanarFaces.h"
#include "strata/mesh/MeshCheck.h"

using namespace strata;
using mesh::Mesh;

namespace {

// `count` unit cubes in a row, 2 apart; each face four triangles around a
// point at its centre, which the join must drop.
Mesh cutCubes(int count) {
    Mesh m;
    // The cube's faces as corner indices (0..7 = x + 2y + 4z), counter-clockwise from outside.
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int c = 0; c < count; ++c) {
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        for (int i = 0; i < 8; ++i) m.positions.push_back({2.0 * c + (i & 1), (i >> 1) & 1, (i >> 2) & 1});
        for (const auto& f : faces) {
            glm::dvec3 centre(0.0);
            for (std::uint32_t k : f) centre += m.positions[base + k] / 4.0;
            const auto mid = static_cast<std::uint32_t>(m.positions.size());
            m.positions.push_back(centre);
            for (int k = 0; k < 4; ++k) m.triangles.push_back({base + f[k], base + f[(k + 1) % 4], mid});
        }
    }
    return m;
}

Mesh meshOf(const exact::detail::ExactSolid& s) {
    Mesh m;
    for (auto v : s.vertices())
        m.positions.push_back({CGAL::to_double(s.point(v).x()), CGAL::to_double(s.point(v).y()),
                               CGAL::to_double(s.point(v).z())});
    for (auto f : s.faces()) {
        std::array<std::uint32_t, 3> t{};
        int i = 0;
        for (auto v : CGAL::vertices_around_face(s.halfedge(f), s)) t[static_cast<std::size_t>(i++)] = v.idx();
        m.triangles.push_back(t);
    }
    return m;
}

}  // namespace

TEST(JoinedCoplanarFaces, ManyRegionsAtOnceComeOutAsEachAloneWould) {
    // 400 cubes: 2,400 regions to triangulate afresh, more than one batch
    // per thread on any machine with up to 9 cores.
    const int count = 400;
    const exact::detail::ExactSolid cut = exact::detail::toExactSolid(cutCubes(count), SourceLocation{}, "the test");
    const Mesh joined = meshOf(exact::detail::joinedCoplanarFaces(cut));
    EXPECT_EQ(joined.positions.size(), std::size_t(8 * count));  // the centres gone
    EXPECT_EQ(joined.triangles.size(), std::size_t(12 * count));  // two triangles a face
    EXPECT_NEAR(mesh::test::signedVolume(joined), double(count), 1e-9);
    EXPECT_TRUE(mesh::checkMesh(joined).ok()) << mesh::checkMesh(joined).describe();
    // Each cube's own eight corners and twelve triangles: no triangle
    // spans two cubes, whichever thread made it.
    for (const auto& t : joined.triangles) {
        const int cube = static_cast<int>(joined.positions[t[0]].x / 2.0);
        for (std::uint32_t v : t) EXPECT_EQ(static_cast<int>(joined.positions[v].x / 2.0), cube);
    }
}
