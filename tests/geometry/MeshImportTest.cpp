#include "strata/geometry/MeshImport.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "GeometryTestUtil.h"
#include "strata/core/Error.h"
#include "strata/geometry/MeshCheck.h"

using namespace strata;
using namespace strata::geometry;
using strata::geometry::test::signedVolume;
using strata::geometry::test::surfaceArea;

namespace {

std::string meshPath(const std::string& name) { return std::string(STRATA_TEST_DIR) + "/data/meshes/" + name; }

// A fresh folder under the system temp dir, removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("strata_geometry_" + std::string(info->test_suite_name()) + "_" + info->name());
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

// Binary STL: 80-byte header, uint32 count, then per triangle 12 floats
// (normal, three vertices) and a uint16 attribute, all little endian.
void writeBinaryStl(const std::string& path, const std::vector<std::array<glm::vec3, 3>>& triangles) {
    std::ofstream out(path, std::ios::binary);
    char header[80] = {};
    std::strncpy(header, "binary STL written by strata's tests", sizeof header - 1);
    out.write(header, sizeof header);
    const auto count = static_cast<uint32_t>(triangles.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : triangles) {
        const glm::vec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
        out.write(reinterpret_cast<const char*>(&n), 12);
        for (const auto& p : t) out.write(reinterpret_cast<const char*>(&p), 12);
        const uint16_t attribute = 0;
        out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
}

std::vector<std::array<glm::vec3, 3>> unitCubeTriangles() {
    const glm::vec3 v[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<std::array<glm::vec3, 3>> t;
    for (const auto& q : quads) {
        t.push_back({v[q[0]], v[q[1]], v[q[2]]});
        t.push_back({v[q[0]], v[q[2]], v[q[3]]});
    }
    return t;
}

void expectUnitCube(const Mesh& m) {
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_NEAR(signedVolume(m), 1.0, 1e-12);
    EXPECT_NEAR(surfaceArea(m), 6.0, 1e-12);
    const Bounds b = boundsOf(m);
    EXPECT_EQ(b.min, glm::dvec3(0, 0, 0));
    EXPECT_EQ(b.max, glm::dvec3(1, 1, 1));
}

}  // namespace

TEST(ImportMesh, ReadsAsciiStlWithVerticesMerged) { expectUnitCube(importMesh(meshPath("cube_ascii.stl"))); }

TEST(ImportMesh, ReadsBinaryStl) {
    TempDir dir;
    writeBinaryStl(dir.file("cube.stl"), unitCubeTriangles());
    expectUnitCube(importMesh(dir.file("cube.stl")));
}

TEST(ImportMesh, ReadsOffObjWithQuads) {
    expectUnitCube(importMesh(meshPath("cube.off")));
    expectUnitCube(importMesh(meshPath("cube.obj")));
}

TEST(ImportMesh, ReadsOffWithCountsOnTheKeywordLineAsOpenScadWritesIt) {
    expectUnitCube(importMesh(meshPath("cube_openscad.off")));
}

TEST(ImportMesh, ReadsPly) {
    const Mesh m = importMesh(meshPath("tetrahedron.ply"));
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 4u);
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_NEAR(signedVolume(m), 8.0 / 6.0, 1e-12);
}

TEST(ImportMesh, EarClipsNonConvexFaces) {
    // The L-shaped prism: two hexagon caps of area 3, height 2, perimeter 8.
    const Mesh m = importMesh(meshPath("l_prism.obj"));
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_NEAR(signedVolume(m), 6.0, 1e-12);
    EXPECT_NEAR(surfaceArea(m), 2 * 3 + 8 * 2, 1e-12);
}

TEST(ImportMesh, ExtensionIsCaseInsensitive) {
    TempDir dir;
    std::filesystem::copy_file(meshPath("cube.off"), dir.file("CUBE.OFF"));
    writeBinaryStl(dir.file("Cube.Stl"), unitCubeTriangles());
    expectUnitCube(importMesh(dir.file("CUBE.OFF")));
    expectUnitCube(importMesh(dir.file("Cube.Stl")));
}

TEST(ImportMesh, OpenMeshReadsButChecksFail) {
    const MeshCheck c = checkMesh(importMesh(meshPath("open_box.off")));
    EXPECT_EQ(c.boundaryEdges, 4u);
    EXPECT_EQ(c.describe(), "not closed: 4 boundary edges");
}

TEST(ImportMesh, ComplexEdgesStayVisibleToTheCheck) {
    // Two cubes sharing one edge: OpenMesh cannot attach the faces around that
    // edge and re-adds them on copies of their vertices; the check must still
    // see four triangles on the shared edge, two running each way: a solid
    // that touches itself, which is valid.
    const Mesh m = importMesh(meshPath("two_cubes_sharing_edge.off"));
    EXPECT_EQ(m.triangles.size(), 24u);
    const MeshCheck c = checkMesh(m);
    EXPECT_TRUE(c.ok()) << c.describe();
    EXPECT_EQ(c.touchingEdges, 1u);
    EXPECT_EQ(c.nonManifoldEdges, 0u);
    EXPECT_EQ(c.boundaryEdges, 0u);
}

TEST(ImportMesh, MissingFileThrowsNamingIt) {
    const std::string path = meshPath("no_such_mesh.stl");
    try {
        importMesh(path);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": cannot read mesh: no such file");
    }
}

TEST(ImportMesh, BadFilesThrow) {
    TempDir dir;
    { std::ofstream(dir.file("empty.stl")); }
    { std::ofstream(dir.file("short.stl"), std::ios::binary) << "abc"; }
    { std::ofstream(dir.file("cube.xyz")) << "1 2 3\n"; }
    { std::ofstream(dir.file("huge.off")) << "OFF\n4000000000 4000000000 0\n0 0 0\n"; }
    { std::ofstream(dir.file("huge_inline.off")) << "OFF 99999999999 1 0\n0 0 0\n3 0 0 0\n"; }
    {
        std::ofstream(dir.file("huge.ply")) << "ply\nformat ascii 1.0\nelement vertex 4000000000\n"
                                              "property float x\nproperty float y\nproperty float z\n"
                                              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n";
    }
    for (const std::string& p : {meshPath("garbage.off"), dir.file("empty.stl"), dir.file("short.stl"), dir.file("cube.xyz"),
                                 dir.file(""), dir.file("huge.off"), dir.file("huge_inline.off"),
                                 dir.file("huge.ply")}) {
        try {
            importMesh(p);
            ADD_FAILURE() << p << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(p + ": cannot read mesh: ", 0), 0u) << e.what();
        }
    }
}

TEST(ImportMesh, NonFiniteCoordinatesNameTheirLine) {
    TempDir dir;
    const std::string tetrahedron = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    { std::ofstream(dir.file("nan.off")) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 nan\n0 0 1\n" << tetrahedron; }
    { std::ofstream(dir.file("inf.obj")) << "# made by hand\no inf\nv 0 0 0\nv 1 0 0\nv 0 -INF 0\nv 0 0 1\nf 1 3 2\n"; }
    // Names that merely spell the word are names, not numbers.
    { std::ofstream(dir.file("named.obj")) << "# inf\no inf\ng nan\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"; }
    for (const auto& [name, line] : {std::pair<const char*, int>{"nan.off", 5}, {"inf.obj", 5}}) {
        try {
            importMesh(dir.file(name));
            ADD_FAILURE() << name << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()),
                      dir.file(name) + ":" + std::to_string(line) + ": cannot read mesh: a coordinate is not a finite number");
        }
    }
    EXPECT_EQ(importMesh(dir.file("named.obj")).positions.size(), 4u);
}
