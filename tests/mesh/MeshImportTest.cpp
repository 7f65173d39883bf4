#include "strata/mesh/MeshImport.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

#include "MeshTestUtil.h"
#include "strata/core/Error.h"
#include "strata/mesh/MeshCheck.h"

using namespace strata;
using namespace strata::mesh;
using strata::mesh::test::signedVolume;
using strata::mesh::test::surfaceArea;

namespace {

std::string meshPath(const std::string& name) { return std::string(STRATA_TEST_DIR) + "/data/meshes/" + name; }

// Whether an import error starts with the file, or with the file and a line:
// "path: cannot read mesh: ..." or "path:12: cannot read mesh: ...".
bool namesTheFile(const std::string& message, const std::string& path) {
    if (message.rfind(path + ": cannot read mesh: ", 0) == 0) return true;
    if (message.rfind(path + ":", 0) != 0) return false;
    std::size_t i = path.size() + 1;
    const std::size_t digits = i;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
    return i > digits && message.compare(i, 20, ": cannot read mesh: ") == 0;
}

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

TEST(ImportMesh, AnObjsMaterialFilesAreNeverOpened) {
    // mtllib naming a FIFO that nobody writes would block the reader for
    // good, and /dev/zero would be read without end: neither is opened.
    TempDir dir;
    ASSERT_EQ(::mkfifo(dir.file("blocks.mtl").c_str(), 0600), 0);
    std::ifstream cube(meshPath("cube.obj"));
    const std::string body((std::istreambuf_iterator<char>(cube)), std::istreambuf_iterator<char>());
    std::ofstream(dir.file("fifo.obj")) << "mtllib blocks.mtl\n" << body;
    std::ofstream(dir.file("zero.obj")) << "  mtllib /dev/zero\n" << body;
    expectUnitCube(importMesh(dir.file("fifo.obj")));
    expectUnitCube(importMesh(dir.file("zero.obj")));
}

TEST(ImportMesh, AnObjsCornersMayNameTextureAndNormalAndCountBack) {
    // The unit tetrahedron with every form of corner reference: plain,
    // v/vt, v//vn, v/vt/vn, negative (from the last vertex read), vertex
    // colours after the coordinates, a line continued with a backslash,
    // and statements strata skips. Its volume is 1/6 whichever way the
    // corners are written, and the faces point outward.
    TempDir dir;
    std::ofstream(dir.file("forms.obj")) << "# forms\r\no t\ng a b\ns off\nusemtl m\n"
                                         << "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n"
                                         << "f 1 3 2\nf 1/1 2/1 4/1\nf 1//1 \\\n 4//1 3//1\nf -3/1/1 -2/1/1 -1/1/1\nl 1 2\n";
    const Mesh m = importMesh(dir.file("forms.obj"));
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 4u);
    EXPECT_TRUE(checkMesh(m).ok()) << checkMesh(m).describe();
    EXPECT_NEAR(signedVolume(m), 1.0 / 6.0, 1e-15);
}

TEST(ImportMesh, AnObjsBadFaceOrVertexIsOneLineNamingIt) {
    // A face naming vertices that do not exist made OpenMesh's reader
    // assert (found by the OBJ fuzzer); each fault is one line here.
    TempDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"mtllmtllib /dev/zero\nv0 0 1\nf 1 3 2\n", ":3: cannot read mesh: a face refers to vertex 1, but 0 vertices are defined before it"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", ":4: cannot read mesh: a face refers to vertex -4, but 3 vertices are defined before it"},
        {"v 0 0 0\nv 1 0 0\nf 1 2\n", ":3: cannot read mesh: a face needs at least three corners"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n", ":4: cannot read mesh: 'x' is not a vertex reference"},
        {"v 0 0\n", ":1: cannot read mesh: a vertex needs three coordinates"},
        {"v 0 0 0\nv 1 0 one\n", ":2: cannot read mesh: 'one' is not a number"},
        {"v 0 0 0\n", ": cannot read mesh: no faces (not a valid obj file?)"},
    };
    for (const auto& [text, message] : cases) {
        { std::ofstream(dir.file("bad.obj")) << text; }
        try {
            importMesh(dir.file("bad.obj"));
            ADD_FAILURE() << text << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), dir.file("bad.obj") + message) << text;
        }
    }
}

TEST(ImportMesh, ReadsOffsWithGeomviewsPrefixesAndComments) {
    // The unit tetrahedron as COFF (a colour after each vertex and face),
    // nOFF (its dimension first), 4OFF (homogeneous: every coordinate
    // doubled, w = 2) and with comments and blank lines between everything.
    TempDir dir;
    const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3 1 0 0\n";
    std::ofstream(dir.file("c.off")) << "COFF\n4 4 6\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n0 0 1 1 1 1 1\n" << faces;
    std::ofstream(dir.file("n.off")) << "nOFF 3\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" << faces;
    std::ofstream(dir.file("4.off")) << "4OFF\n4 4 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n0 0 2 2\n" << faces;
    std::ofstream(dir.file("comments.off")) << "# a tetrahedron\nOFF # keyword\n\n4 4 0\n# vertices\n0 0 0\n1 0 0\n\n0 1 0\n0 0 1 # last\n"
                                            << faces;
    for (const char* name : {"c.off", "n.off", "4.off", "comments.off"}) {
        const Mesh m = importMesh(dir.file(name));
        EXPECT_EQ(m.triangles.size(), 4u) << name;
        EXPECT_TRUE(checkMesh(m).ok()) << name << ": " << checkMesh(m).describe();
        EXPECT_NEAR(signedVolume(m), 1.0 / 6.0, 1e-15) << name;
    }
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
    // The vertices' count alone reads as a number: OpenMesh made them all (found by the OFF fuzzer).
    { std::ofstream(dir.file("huge_vertices.off")) << "OFF\n21474836\xaa" "47 1 0\n0 0 0\n3 0 1 2\n"; }
    {
        std::ofstream(dir.file("huge.ply")) << "ply\nformat ascii 1.0\nelement vertex 4000000000\n"
                                              "property float x\nproperty float y\nproperty float z\n"
                                              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n";
    }
    for (const std::string& p : {meshPath("garbage.off"), dir.file("empty.stl"), dir.file("short.stl"), dir.file("cube.xyz"),
                                 dir.file(""), dir.file("huge.off"), dir.file("huge_inline.off"),
                                 dir.file("huge_vertices.off"), dir.file("huge.ply")}) {
        try {
            importMesh(p);
            ADD_FAILURE() << p << ": expected an error";
        } catch (const Error& e) {
            EXPECT_TRUE(namesTheFile(e.what(), p)) << e.what();
        }
    }
    // Found by the OFF fuzzer: a header whose counts do not read as numbers
    // (OpenMesh reserved 6 GB for it), a text header holding the word BINARY
    // (OpenMesh read it as text and reserved 2 GB), and binary OFF.
    { std::ofstream(dir.file("no_counts.off"), std::ios::binary) << "OFF OF\xf8"; }
    {
        std::ofstream out(dir.file("binary.off"), std::ios::binary);
        const std::int32_t counts[3] = {1 << 30, 1, 0};
        out << "OFF BINARY\n";
        out.write(reinterpret_cast<const char*>(counts), sizeof counts);
    }
    { std::ofstream(dir.file("binary_in_text.off"), std::ios::binary) << "OFF 8 6\xef\xbf\xbf" "BINARY\xff\n0 0 0\n"; }
    // Each with the line named where there is one; bytes that are not
    // printable are written out.
    const std::tuple<const char*, const char*, const char*> refused[] = {
        {"huge_vertices.off", ":2: ", "'21474836\\xaa47' is not a number"},
        {"no_counts.off", ":1: ", "'OF\\xf8' is not a number"},
        {"binary.off", ": ", "binary OFF is not read (write the mesh as text OFF, STL or PLY)"},
        {"binary_in_text.off", ":1: ", "'6\\xef\\xbf\\xbfBINARY\\xff' is not a number"},
    };
    for (const auto& [name, where, why] : refused) {
        try {
            importMesh(dir.file(name));
            ADD_FAILURE() << name << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), dir.file(name) + where + "cannot read mesh: " + why);
        }
    }
}

namespace {

// A PLY header: the magic line, the format, then `rest`.
std::string plyHeader(const std::string& format, const std::string& rest) {
    return "ply\nformat " + format + " 1.0\n" + rest;
}

const std::string kTetrahedronElements =
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\n";
const std::string kTetrahedronBody = "0 0 0\n2 0 0\n0 2 0\n0 0 2\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// The tetrahedron of tetrahedron.ply in a binary PLY of either byte order.
std::string binaryTetrahedron(bool little) {
    std::string text = plyHeader(little ? "binary_little_endian" : "binary_big_endian",
                                 "comment written by strata's tests\n" + kTetrahedronElements + "end_header\n");
    auto put = [&](const void* data, std::size_t n) {
        const auto* bytes = static_cast<const char*>(data);
        for (std::size_t i = 0; i < n; ++i) text += bytes[little ? i : n - 1 - i];  // the test machine is little endian
    };
    const float points[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    for (const auto& p : points)
        for (float c : p) put(&c, 4);
    const int32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces) {
        text += '\3';
        for (int32_t i : f) put(&i, 4);
    }
    return text;
}

}  // namespace

TEST(ImportMesh, ReadsBinaryAndCrlfPly) {
    TempDir dir;
    std::string crlf;
    for (char c : plyHeader("ascii", kTetrahedronElements + "end_header\n") + kTetrahedronBody) {
        if (c == '\n') crlf += '\r';
        crlf += c;
    }
    std::ofstream(dir.file("crlf.ply"), std::ios::binary) << crlf;
    std::ofstream(dir.file("little.ply"), std::ios::binary) << binaryTetrahedron(true);
    std::ofstream(dir.file("big.ply"), std::ios::binary) << binaryTetrahedron(false);
    for (const char* name : {"crlf.ply", "little.ply", "big.ply"}) {
        const Mesh m = importMesh(dir.file(name));
        EXPECT_EQ(m.triangles.size(), 4u) << name;
        EXPECT_NEAR(signedVolume(m), 8.0 / 6.0, 1e-12) << name;
    }
}

// OpenMesh's PLY reader crashes on a property before any element and never
// returns from a header without end_header; it also believes every count.
// Each of these files is refused with one line naming it, before OpenMesh
// reads it.
TEST(ImportMesh, HostilePlyFilesAreRefusedWithOneLine) {
    TempDir dir;
    const std::string ascii = plyHeader("ascii", "");
    const std::string vertexXyz = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string faceList = "element face 4\nproperty list uchar int vertex_indices\n";
    std::string longComments;
    while (longComments.size() < 70000) longComments += "comment a header that goes on and on\n";
    std::string binaryShort = binaryTetrahedron(true);
    binaryShort.resize(binaryShort.size() - 5);  // the last face's last index cut off
    std::string binaryNoFace = binaryTetrahedron(true);
    binaryNoFace.resize(binaryNoFace.size() - 13);  // the last face missing
    std::string binaryLongList = binaryTetrahedron(false);
    binaryLongList[binaryLongList.size() - 13] = '\xff';  // the last face: a list of 255 indices

    const std::vector<std::pair<std::string, std::string>> cases = {
        // 49 bytes: a property with no element.
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", ":3: cannot read mesh: a property before any element"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", ": cannot read mesh: the header has no end_header line"},
        {ascii + longComments + kTetrahedronElements + "end_header\n" + kTetrahedronBody,
         ": cannot read mesh: no end_header in the first 65536 bytes"},
        {"PLY\nformat ascii 1.0\n", ": cannot read mesh: not a PLY file (its first line is not 'ply')"},
        {"ply\nformat utf8 1.0\nend_header\n",
         ":2: cannot read mesh: unknown format 'utf8' (expected ascii, binary_little_endian or binary_big_endian)"},
        {"ply\nformat ascii 2.0\nend_header\n", ":2: cannot read mesh: unknown format version '2.0' (expected 1.0)"},
        {"ply\nelement vertex 4\nend_header\n", ":2: cannot read mesh: expected the format line, got 'element'"},
        {ascii + "format ascii 1.0\nend_header\n", ":3: cannot read mesh: a second format line"},
        {ascii + "element vertex\nend_header\n", ":3: cannot read mesh: expected 'element NAME COUNT'"},
        {ascii + "element vertex -4\nend_header\n", ":3: cannot read mesh: the count of element 'vertex' is not a whole number: '-4'"},
        {ascii + "element vertex 4\nproperty float128 x\nend_header\n", ":4: cannot read mesh: unknown property type 'float128'"},
        {ascii + vertexXyz + "element face 4\nproperty list float int vertex_indices\nend_header\n",
         ":8: cannot read mesh: a list's length type must be an integer type, not 'float'"},
        {ascii + "element vertex 4\nproperty float x\nfacet \x01\x02\nend_header\n",
         ":5: cannot read mesh: unknown header line starting with 'facet'"},
        {ascii + "elem\x01nt vertex 4\nend_header\n", ":3: cannot read mesh: unknown header line starting with 'elem\\x01nt'"},
        // Counts no file of this size can hold.
        {ascii + "element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n" + faceList +
             "end_header\n" + kTetrahedronBody,
         ":3: cannot read mesh: header declares 4000000000 'vertex' elements, more than the file can hold"},
        {ascii + "element vertex 18446744073709551615\nproperty float x\nproperty float y\nproperty float z\n" + faceList +
             "end_header\n" + kTetrahedronBody,
         ":3: cannot read mesh: header declares 18446744073709551615 'vertex' elements, more than the file can hold"},
        {ascii + "element vertex 99999999999999999999999\n" + faceList + "end_header\n",
         ":3: cannot read mesh: header declares '99999999999999999999999' 'vertex' elements, more than the file can hold"},
        {plyHeader("binary_little_endian", "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n" +
                                                faceList + "end_header\n") + std::string(64, '\0'),
         ":3: cannot read mesh: header declares 4 'vertex' elements, more than the file can hold"},
        // Binary types OpenMesh's reader does not take (it printed a line per
        // coordinate and read zeros, or stopped at the first face).
        {plyHeader("binary_little_endian", "element vertex 4\nproperty short x\nproperty short y\nproperty short z\n" +
                                                faceList + "end_header\n") + std::string(64, '\0'),
         ":4: cannot read mesh: binary coordinates of type 'short' are not read (float or double are)"},
        {plyHeader("binary_big_endian", vertexXyz + "element face 4\nproperty list ushort int vertex_indices\nend_header\n") +
             std::string(80, '\0'),
         ":8: cannot read mesh: a binary face's corner count of type 'ushort' is not read (uchar or int is)"},
        {ascii + vertexXyz + "element face 5\nproperty list uchar int vertex_indices\nend_header\n" + kTetrahedronBody,
         ": cannot read mesh: the file ends before the 5 'face' elements its header declares"},
        // What a mesh needs.
        {ascii + faceList + "end_header\n3 0 1 2\n3 0 1 2\n3 0 1 2\n3 0 1 2\n", ": cannot read mesh: the header declares no vertex element"},
        {ascii + "element vertex 4\nproperty float x\nproperty float y\n" + faceList + "end_header\n" + kTetrahedronBody,
         ":3: cannot read mesh: the vertex element has no property z"},
        {ascii + vertexXyz + "end_header\n0 0 0\n2 0 0\n0 2 0\n0 0 2\n", ": cannot read mesh: the header declares no face element"},
        {ascii + vertexXyz + "element face 4\nproperty int flags\nend_header\n" + kTetrahedronBody,
         ":7: cannot read mesh: the face element has no list property vertex_indices"},
        {ascii + faceList + vertexXyz + "end_header\n" + kTetrahedronBody, ":3: cannot read mesh: the face element comes before the vertex element"},
        // Bodies that do not hold what the header says.
        {ascii + kTetrahedronElements + "end_header\n" + kTetrahedronBody.substr(0, kTetrahedronBody.size() - 8) + "       \n",
         ": cannot read mesh: the file ends before the 4 'face' elements its header declares"},
        {ascii + kTetrahedronElements + "end_header\n0 0 0\n2 0 0\n0 2 0\n0 0 2\n2000000000 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
         ":14: cannot read mesh: a list of 2000000000 values, more than the file holds"},
        {ascii + kTetrahedronElements + "end_header\n0 0 0\n2 0 0\n0 2 0\n0 0 2\n3.5 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
         ":14: cannot read mesh: a list length that is not a whole number: '3.5'"},
        // Words OpenMesh's >> would split: '0+0' is read as 0 and +0, and
        // every value after it shifts by one (the fuzzer's case: a list
        // length of 120 digits further on, and 2 GB of vertex handles).
        {ascii + kTetrahedronElements + "end_header\n0 0 0\n2 0 0\n0 2 0\n0+0 2\n3 0 2 1\n3 0 1 3\n3 00 0 0\n" +
             std::string(120, '2') + "03 2\n",
         ":13: cannot read mesh: a value that is not a number: '0+0'"},
        {ascii + kTetrahedronElements + "end_header\n0 0 0\n2 0 0\n0 2 0\n0 0 2\n3 0 2 1\n3 0 1.5 3\n3 0 3 2\n3 1 2 3\n",
         ":15: cannot read mesh: a value that is not a whole number: '1.5'"},
        {binaryShort, ": cannot read mesh: a list of 3 values in element 'face', more than the file holds"},
        {binaryNoFace, ": cannot read mesh: the file ends before the 4 'face' elements its header declares"},
        {binaryLongList, ": cannot read mesh: a list of 255 values in element 'face', more than the file holds"},
    };
    int n = 0;
    for (const auto& [text, message] : cases) {
        const std::string path = dir.file("hostile" + std::to_string(n++) + ".ply");
        std::ofstream(path, std::ios::binary) << text;
        try {
            importMesh(path);
            ADD_FAILURE() << path << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), path + message);
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
