// Mesh files as strata writes them, read back by parsers written here from
// the formats' definitions (binary STL, OFF, OBJ) and by lib3mf's own reader
// (3MF): every point and triangle comes back, and the file names its format.

#include <gtest/gtest.h>

#include <unistd.h>

#include <Model/COM/NMR_DLLInterfaces.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "strata/core/Error.h"
#include "strata/io/MeshWriter.h"
#include "ThreeMfFile.h"

using namespace strata;

namespace {

// A unit tetrahedron, outward.
mesh::Mesh tetrahedron() {
    mesh::Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.1 + 0.2}};  // 0.30000000000000004: a double OFF must keep
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

std::string text(const std::vector<unsigned char>& bytes) { return std::string(bytes.begin(), bytes.end()); }

TEST(MeshWriter, FormatsAreChosenByTheExtension) {
    EXPECT_EQ(io::meshFormatOf("a.stl"), io::MeshFormat::Stl);
    EXPECT_EQ(io::meshFormatOf("dir/a.OFF"), io::MeshFormat::Off);
    EXPECT_EQ(io::meshFormatOf("a.Obj"), io::MeshFormat::Obj);
    EXPECT_EQ(io::meshFormatOf("a.3mf"), io::MeshFormat::ThreeMf);
    try {
        io::meshFormatOf("a.ply");
        ADD_FAILURE() << "a .ply export was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "a.ply: cannot export to '.ply' (expected .stl, .off, .obj or .3mf)");
    }
}

TEST(MeshWriter, BinaryStlHoldsEveryTriangleWithItsNormal) {
    const mesh::Mesh m = tetrahedron();
    const std::vector<unsigned char> bytes = io::meshBytes(m, io::MeshFormat::Stl);
    ASSERT_EQ(bytes.size(), 84u + 50u * m.triangles.size());
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    EXPECT_EQ(count, m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        float f[12];
        std::memcpy(f, bytes.data() + 84 + 50 * t, sizeof f);
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& p = m.positions[m.triangles[t][static_cast<std::size_t>(k)]];
            EXPECT_EQ(f[3 + 3 * k], static_cast<float>(p.x));
            EXPECT_EQ(f[4 + 3 * k], static_cast<float>(p.y));
            EXPECT_EQ(f[5 + 3 * k], static_cast<float>(p.z));
        }
    }
    // The first triangle lies in z = 0, wound to face down.
    float normal[3];
    std::memcpy(normal, bytes.data() + 84, sizeof normal);
    EXPECT_EQ(normal[0], 0.0f);
    EXPECT_EQ(normal[1], 0.0f);
    EXPECT_EQ(normal[2], -1.0f);
}

TEST(MeshWriter, OffAndObjKeepEveryDoubleExactly) {
    const mesh::Mesh m = tetrahedron();
    {
        std::istringstream in(text(io::meshBytes(m, io::MeshFormat::Off)));
        std::string magic;
        std::size_t v = 0, f = 0, e = 0;
        in >> magic >> v >> f >> e;
        EXPECT_EQ(magic, "OFF");
        ASSERT_EQ(v, m.positions.size());
        ASSERT_EQ(f, m.triangles.size());
        for (const glm::dvec3& p : m.positions) {
            double x, y, z;
            in >> x >> y >> z;
            EXPECT_EQ(x, p.x);
            EXPECT_EQ(y, p.y);
            EXPECT_EQ(z, p.z);
        }
        for (const auto& t : m.triangles) {
            int n, a, b, c;
            in >> n >> a >> b >> c;
            EXPECT_EQ(n, 3);
            EXPECT_EQ((std::array<int, 3>{a, b, c}), (std::array<int, 3>{int(t[0]), int(t[1]), int(t[2])}));
        }
    }
    {
        std::istringstream in(text(io::meshBytes(m, io::MeshFormat::Obj)));
        std::string line;
        std::vector<glm::dvec3> points;
        std::vector<std::array<int, 3>> faces;
        while (std::getline(in, line)) {
            std::istringstream words(line);
            std::string kind;
            words >> kind;
            if (kind == "v") {
                glm::dvec3 p;
                words >> p.x >> p.y >> p.z;
                points.push_back(p);
            } else if (kind == "f") {
                std::array<int, 3> f{};
                words >> f[0] >> f[1] >> f[2];
                faces.push_back(f);
            }
        }
        ASSERT_EQ(points.size(), m.positions.size());
        for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points[i], m.positions[i]);
        ASSERT_EQ(faces.size(), m.triangles.size());
        EXPECT_EQ(faces[3], (std::array<int, 3>{2, 3, 4}));  // OBJ counts from 1
    }
}

TEST(MeshWriter, ThreeMfReadsBackThroughLib3mfWithItsColours) {
    const mesh::Mesh m = tetrahedron();
    const std::vector<glm::vec4> colors{{1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0.5f, 1, 1}, {1, 0, 0, 1}};
    std::vector<unsigned char> bytes = io::meshBytes(m, io::MeshFormat::ThreeMf, colors);
    ASSERT_GT(bytes.size(), 4u);
    EXPECT_EQ(bytes[0], 'P');  // a zip archive
    EXPECT_EQ(bytes[1], 'K');

    const strata::testing::ThreeMfFile file(bytes);
    NMR::PLib3MFModelResource* resource = file.mesh();
    DWORD vertices = 0, triangles = 0;
    EXPECT_EQ(NMR::lib3mf_meshobject_getvertexcount(resource, &vertices), LIB3MF_OK);
    EXPECT_EQ(NMR::lib3mf_meshobject_gettrianglecount(resource, &triangles), LIB3MF_OK);
    EXPECT_EQ(vertices, m.positions.size());
    EXPECT_EQ(triangles, m.triangles.size());
    NMR::MODELMESHVERTEX apex{};
    EXPECT_EQ(NMR::lib3mf_meshobject_getvertex(resource, 3, &apex), LIB3MF_OK);
    EXPECT_EQ(apex.m_fPosition[2], static_cast<float>(m.positions[3].z));
    // Two distinct colours: two base materials, the third triangle the second one.
    ASSERT_NE(file.materials(), nullptr);
    DWORD materials = 0;
    EXPECT_EQ(NMR::lib3mf_basematerial_getcount(file.materials(), &materials), LIB3MF_OK);
    EXPECT_EQ(materials, 2u);
    DWORD groupId = 0, first = 0, third = 0;
    EXPECT_EQ(NMR::lib3mf_propertyhandler_getbasematerial(file.properties(), 0, &groupId, &first), LIB3MF_OK);
    EXPECT_EQ(NMR::lib3mf_propertyhandler_getbasematerial(file.properties(), 2, &groupId, &third), LIB3MF_OK);
    EXPECT_NE(first, third);
}

TEST(MeshWriter, StagedMeshesAreWrittenWholeOrNotAtAll) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("strata-mesh-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        io::StagedFile staged = io::stageMesh((dir / "t.off").string(), tetrahedron());
        EXPECT_FALSE(std::filesystem::exists(dir / "t.off"));
        staged.commit();
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "t.off"));
    EXPECT_THROW(io::stageMesh((dir / "missing/t.stl").string(), tetrahedron()), Error);
    EXPECT_THROW(io::stageMesh((dir / "t.ply").string(), tetrahedron()), Error);
    std::filesystem::remove_all(dir);
}

}  // namespace
