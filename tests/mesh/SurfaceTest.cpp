#include "strata/mesh/Surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "MeshTestUtil.h"
#include "strata/core/Error.h"
#include "strata/mesh/MeshCheck.h"

// surface() against OpenSCAD 2021.01's own meshes: tests/data/flat/surface/
// holds the inputs and `openscad -o NAME.off NAME.scad` (see its README.md).
// OFF keeps OpenSCAD's polygons, written with 6 significant digits; the
// expected triangles are those polygons split as OpenSCAD's preview splits
// them (a quad (0,1,2,3) into (0,1,3) and (2,3,1), a larger polygon into a
// fan around its vertex average).

using namespace strata;
using namespace strata::mesh;

namespace {

const std::string kDir = std::string(STRATA_TEST_DIR) + "/data/flat/surface/";

// A number as OpenSCAD's OFF export prints it (std::ostream, precision 6); -0 as 0.
std::string print(double v) {
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os << v;
    const std::string s = os.str();
    return s == "-0" ? "0" : s;
}

std::string print(const glm::dvec3& p) { return print(p.x) + " " + print(p.y) + " " + print(p.z); }

struct OffFile {
    std::vector<glm::dvec3> vertices;
    std::vector<std::vector<int>> faces;
};

OffFile readOff(const std::string& path) {
    std::ifstream in(path);
    std::string magic;
    std::size_t nv = 0, nf = 0, ne = 0;
    in >> magic >> nv >> nf >> ne;
    EXPECT_EQ(magic, "OFF") << path;
    OffFile off;
    for (std::size_t i = 0; i < nv; ++i) {
        glm::dvec3 p;
        in >> p.x >> p.y >> p.z;
        off.vertices.push_back(p);
    }
    for (std::size_t i = 0; i < nf; ++i) {
        int n = 0;
        in >> n;
        std::vector<int> face(static_cast<std::size_t>(n));
        for (int& v : face) in >> v;
        off.faces.push_back(face);
    }
    EXPECT_TRUE(in.good()) << path;
    return off;
}

using TriangleKey = std::array<std::string, 3>;

// The triangle's printed corners, rotated to start at the smallest.
TriangleKey key(const std::string& a, const std::string& b, const std::string& c) {
    if (a <= b && a <= c) return {a, b, c};
    if (b <= a && b <= c) return {b, c, a};
    return {c, a, b};
}

std::vector<TriangleKey> expectedTriangles(const OffFile& off) {
    std::vector<TriangleKey> out;
    for (const auto& f : off.faces) {
        auto v = [&](std::size_t i) { return print(off.vertices[std::size_t(f[i])]); };
        const std::size_t n = f.size();
        if (n == 3) {
            out.push_back(key(v(0), v(1), v(2)));
        } else if (n == 4) {
            out.push_back(key(v(0), v(1), v(3)));
            out.push_back(key(v(2), v(3), v(1)));
        } else {
            glm::dvec3 sum(0.0);
            for (int i : f) sum += off.vertices[std::size_t(i)];
            const std::string centre = print(sum / double(n));
            for (std::size_t j = 1; j <= n; ++j) out.push_back(key(centre, v(j - 1), v(j % n)));
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<TriangleKey> triangles(const Mesh& m) {
    std::vector<TriangleKey> out;
    for (const auto& t : m.triangles) {
        out.push_back(key(print(m.positions[t[0]]), print(m.positions[t[1]]), print(m.positions[t[2]])));
    }
    std::sort(out.begin(), out.end());
    return out;
}

scene::Surface surface(const std::string& file, bool center = false, bool invert = false) {
    return {kDir + file, center, invert};
}

// The mesh has OpenSCAD's triangles (as printed) and is a closed outward solid.
void expectMatchesOpenScad(const Mesh& mesh, const std::string& offName) {
    const OffFile off = readOff(kDir + offName);
    ASSERT_FALSE(off.faces.empty());
    const MeshCheck check = checkMesh(mesh);
    EXPECT_TRUE(check.ok()) << offName << ": " << check.describe();
    EXPECT_GT(test::signedVolume(mesh), 0.0) << offName;

    const std::vector<TriangleKey> expected = expectedTriangles(off);
    const std::vector<TriangleKey> actual = triangles(mesh);
    EXPECT_EQ(actual.size(), expected.size()) << offName;
    EXPECT_TRUE(actual == expected) << offName << ": the triangles differ from OpenSCAD's";

    // Every OpenSCAD vertex is one of ours and ours are OpenSCAD's plus the base's fan centre.
    std::vector<std::string> theirs, ours;
    for (const auto& p : off.vertices) theirs.push_back(print(p));
    for (const auto& p : mesh.positions) ours.push_back(print(p));
    std::sort(theirs.begin(), theirs.end());
    std::sort(ours.begin(), ours.end());
    ours.erase(std::unique(ours.begin(), ours.end()), ours.end());  // OFF merges coincident vertices
    std::vector<std::string> extra;
    std::set_difference(ours.begin(), ours.end(), theirs.begin(), theirs.end(), std::back_inserter(extra));
    std::vector<std::string> missing;
    std::set_difference(theirs.begin(), theirs.end(), ours.begin(), ours.end(), std::back_inserter(missing));
    EXPECT_TRUE(missing.empty()) << offName << ": " << missing.size() << " OpenSCAD vertices missing";
    EXPECT_LE(extra.size(), 1u) << offName;
}

// For inputs whose every coordinate prints exactly (short decimals), the
// doubles themselves must be OpenSCAD's.
void expectExactVertices(const Mesh& mesh, const std::string& offName) {
    const OffFile off = readOff(kDir + offName);
    auto less = [](const glm::dvec3& a, const glm::dvec3& b) {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    };
    std::vector<glm::dvec3> theirs = off.vertices;
    std::sort(theirs.begin(), theirs.end(), less);
    std::vector<glm::dvec3> ours = mesh.positions;
    std::sort(ours.begin(), ours.end(), less);
    ours.erase(std::unique(ours.begin(), ours.end()), ours.end());  // OFF merges coincident vertices
    std::size_t found = 0;
    for (const auto& p : ours) found += std::binary_search(theirs.begin(), theirs.end(), p, less) ? 1 : 0;
    // All but the base's fan centre, which OpenSCAD's OFF does not have.
    EXPECT_GE(found + 1, ours.size()) << offName;
    EXPECT_EQ(found, off.vertices.size()) << offName;
}

std::string tempFile(const std::string& name, const std::string& content) {
    const auto path = std::filesystem::temp_directory_path() / ("strata_surface_" + name);
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST(SurfaceDat, MatchesOpenScad) {
    const Mesh m = tessellate(surface("bumps.dat"));
    expectMatchesOpenScad(m, "bumps.off");
    expectExactVertices(m, "bumps.off");
    // 4 rows x 5 columns: 12 cells of 4 triangles, 14 side quads, a base of 14 vertices.
    EXPECT_EQ(m.triangles.size(), 12u * 4 + 14 * 2 + 14);
}

TEST(SurfaceDat, CenterAndInvertIgnoredForText) {
    const Mesh m = tessellate(surface("bumps.dat", true, true));
    expectMatchesOpenScad(m, "bumps_center_invert.off");
    expectExactVertices(m, "bumps_center_invert.off");
}

TEST(SurfaceDat, TwoByTwoHasAQuadBase) {
    const Mesh m = tessellate(surface("square.dat", true));
    expectMatchesOpenScad(m, "square.off");
    expectExactVertices(m, "square.off");
    EXPECT_EQ(m.triangles.size(), 4u + 4 * 2 + 2);
}

TEST(SurfaceDat, NumberSyntaxAndCrLf) {
    const Mesh m = tessellate(surface("crlf.dat", true));
    expectMatchesOpenScad(m, "crlf.off");
    expectExactVertices(m, "crlf.off");
}

TEST(SurfaceDat, IllegalValueOnTheLastLineEndsTheData) {
    // "5 x" without a newline: OpenSCAD keeps the 5 and stops, silently.
    const Mesh m = tessellate(surface("trailing.dat"));
    expectMatchesOpenScad(m, "trailing.off");
    expectExactVertices(m, "trailing.off");
}

TEST(SurfacePng, Rgb) { expectMatchesOpenScad(tessellate(surface("rgb.png")), "rgb.off"); }

TEST(SurfacePng, RgbInvertedAndCentred) {
    expectMatchesOpenScad(tessellate(surface("rgb.png", true, true)), "rgb_invert_center.off");
}

TEST(SurfacePng, Grey16KeepsTheHighByte) {
    expectMatchesOpenScad(tessellate(surface("grey16.png", true)), "grey16.off");
}

TEST(SurfacePng, TwoBitPaletteInverted) {
    expectMatchesOpenScad(tessellate(surface("palette.png", false, true)), "palette_invert.off");
}

TEST(SurfacePng, EightBitPaletteInverted) {
    expectMatchesOpenScad(tessellate(surface("palette8.png", false, true)), "palette8_invert.off");
}

// A transparency chunk expands a palette to colour and alpha, which must not
// change the heights; text, gamma and time chunks are not read at all.
TEST(SurfacePng, TransparencyAndAncillaryChunksChangeNothing) {
    expectMatchesOpenScad(tessellate(surface("palette8_chunks.png", false, true)), "palette8_invert.off");
}

TEST(SurfacePng, FourBitGreyInterlaced) {
    expectMatchesOpenScad(tessellate(surface("grey4_interlaced.png")), "grey4_interlaced.off");
}

TEST(SurfacePng, GreyAlphaIgnoresAlpha) {
    expectMatchesOpenScad(tessellate(surface("grey_alpha.png", true)), "grey_alpha.off");
}

TEST(SurfaceEdgeCases, OneRowOrColumnGivesNothing) {
    // OpenSCAD makes a flat sheet without volume; strata makes nothing.
    EXPECT_TRUE(tessellate(surface("row.dat")).triangles.empty());
    EXPECT_TRUE(tessellate({tempFile("column.dat", "1\n2\n3\n"), false, false}).triangles.empty());
}

TEST(SurfaceEdgeCases, EmptyOrCommentOnlyTextGivesNothing) {
    EXPECT_TRUE(tessellate({tempFile("empty.dat", ""), false, false}).triangles.empty());
    EXPECT_TRUE(tessellate({tempFile("comments.dat", "# nothing\n\n   \n# here\n"), false, false}).triangles.empty());
}

TEST(SurfaceErrors, MissingFile) {
    EXPECT_THROW(tessellate(surface("no_such_file.dat")), Error);
    try {
        tessellate(surface("no_such_file.png"));
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("surface: cannot read"), std::string::npos) << e.what();
    }
}

TEST(SurfaceErrors, Directory) { EXPECT_THROW(tessellate({kDir, false, false}), Error); }

TEST(SurfaceErrors, GarbageText) {
    EXPECT_THROW(tessellate({tempFile("garbage.dat", "hello world\n1 2\n"), false, false}), Error);
    EXPECT_THROW(tessellate({tempFile("midgarbage.dat", "1 2\n3 four\n5 6\n"), false, false}), Error);
    EXPECT_THROW(tessellate({tempFile("binary.dat", std::string("\x01\x02\xff\x00\x10\n\n", 7)), false, false}), Error);
}

TEST(SurfaceErrors, NonFiniteValues) {
    EXPECT_THROW(tessellate({tempFile("inf.dat", "1 inf\n2 3\n"), false, false}), Error);
    EXPECT_THROW(tessellate({tempFile("nan.dat", "1 2\nnan 3\n"), false, false}), Error);
}

TEST(SurfaceErrors, TruncatedOrCorruptPng) {
    const std::string png = readBytes(kDir + "rgb.png");
    ASSERT_GT(png.size(), 60u);
    EXPECT_THROW(tessellate({tempFile("truncated.png", png.substr(0, 60)), false, false}), Error);
    EXPECT_THROW(tessellate({tempFile("signature_only.png", png.substr(0, 8)), false, false}), Error);
    std::string corrupt = png;
    corrupt[40] = static_cast<char>(corrupt[40] ^ 0x5a);  // inside the image data: a CRC error
    EXPECT_THROW(tessellate({tempFile("corrupt.png", corrupt), false, false}), Error);
}

TEST(SurfaceErrors, HugePngIsRefusedBeforeDecoding) {
    // A valid header claiming 100000 x 100000 pixels, no image data.
    std::string png = readBytes(kDir + "rgb.png");
    // IHDR width and height are bytes 16..23; the CRC (29..32) is fixed below.
    const unsigned char size[8] = {0x00, 0x01, 0x86, 0xa0, 0x00, 0x01, 0x86, 0xa0};
    for (int i = 0; i < 8; ++i) png[std::size_t(16 + i)] = static_cast<char>(size[i]);
    unsigned long crc = 0xffffffffUL;
    for (std::size_t i = 12; i < 29; ++i) {
        crc ^= static_cast<unsigned char>(png[i]);
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320UL & (0UL - (crc & 1)));
    }
    crc ^= 0xffffffffUL;
    for (int i = 0; i < 4; ++i) png[std::size_t(29 + i)] = static_cast<char>((crc >> (24 - 8 * i)) & 0xff);
    try {
        tessellate({tempFile("huge.png", png), false, false});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
    }
}

TEST(SurfaceErrors, HugeTextGridIsRefused) {
    // Two rows of 4.2 million values: more than 2^24 vertices. Refused while reading.
    std::string text = "1\n1";
    text.reserve(9000000);
    for (int i = 0; i < 4200000; ++i) text += " 0";
    text += "\n";
    EXPECT_THROW(tessellate({tempFile("wide.dat", text), false, false}), Error);
}
