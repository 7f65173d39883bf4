#include "strata/mesh/LastCorners.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "MeshTestUtil.h"
#include "strata/mesh/Primitives.h"

namespace strata::mesh {
namespace {

void expectLayoutOf(const Mesh& mesh) {
    const LastCornerLayout layout = lastCornerLayout(mesh);
    ASSERT_EQ(layout.triangles.size(), mesh.triangles.size());
    ASSERT_GE(layout.source.size(), mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) EXPECT_EQ(layout.source[v], v);
    std::set<std::uint32_t> lasts;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        std::array<std::uint32_t, 3> mapped{};
        for (std::size_t c = 0; c < 3; ++c) {
            ASSERT_LT(layout.triangles[i][c], layout.source.size());
            mapped[c] = layout.source[layout.triangles[i][c]];
        }
        // Same corners in the same order: a rasterizer sets it up alike.
        EXPECT_EQ(mapped, mesh.triangles[i]) << "triangle " << i;
        EXPECT_TRUE(lasts.insert(layout.triangles[i][2]).second) << "triangle " << i << " shares its last corner";
    }
    // No copy is made that no triangle ends on.
    for (std::size_t v = mesh.positions.size(); v < layout.source.size(); ++v) {
        EXPECT_TRUE(lasts.count(static_cast<std::uint32_t>(v))) << "copy " << v << " is no triangle's last";
    }
}

TEST(LastCorners, EveryTriangleEndsOnACornerOfItsOwn) {
    expectLayoutOf(tessellate(scene::Cube{{1, 2, 3}, true}));
    expectLayoutOf(tessellate(scene::Sphere{2.0, scene::Fragments{32.0}}));
    expectLayoutOf(tessellate(scene::Cylinder{2.0, 1.0, 0.0, true, scene::Fragments{7.0}}));
}

TEST(LastCorners, ShuffledTrianglesStillGetOwnCorners) {
    Mesh mesh = tessellate(scene::Sphere{1.0, scene::Fragments{17.0}});
    std::mt19937 rng(7);
    for (auto& t : mesh.triangles) std::rotate(t.begin(), t.begin() + (rng() % 3), t.end());
    std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
    expectLayoutOf(mesh);
}

TEST(LastCorners, CopiesAboutOneVertexInTwo) {
    // A closed genus-0 mesh: F = 2V - 4, so at least V - 4 copies.
    const Mesh mesh = tessellate(scene::Sphere{1.0, scene::Fragments{32.0}});
    const std::size_t copies = lastCornerLayout(mesh).source.size() - mesh.positions.size();
    EXPECT_GE(copies, mesh.positions.size() - 4);
    EXPECT_LE(copies, mesh.triangles.size() * 3 / 4);
}

TEST(LastCorners, EmptyMeshGivesEmptyLayout) {
    const LastCornerLayout layout = lastCornerLayout(Mesh{});
    EXPECT_TRUE(layout.source.empty());
    EXPECT_TRUE(layout.triangles.empty());
}

}  // namespace
}  // namespace strata::mesh
