#include "strata/flat/FlatImport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <polyclipping/clipper.hpp>

#include "strata/core/Error.h"

// import() of DXF and SVG files against OpenSCAD 2021.01: tests/data/flat/import/
// holds the inputs and, for each NAME.scad there, `openscad -o NAME.svg NAME.scad`
// (see its README.md). The .scad files scale the import by 2^16, so OpenSCAD
// writes its 1/65536 grid as whole numbers, exactly (6 significant digits
// suffice below 15.2 units). strata's outlines go through the clean-up the
// caller applies (OpenSCAD's ClipperUtils::sanitize: points times 2^16,
// truncated; unsanitized outlines turned to point up; an even-odd union;
// CleanPolygon) and must give the same outlines, vertex for vertex.

using namespace strata;
using namespace strata::flat;

namespace {

const std::string kDir = std::string(STRATA_TEST_DIR) + "/data/flat/import/";

using GridPoint = std::pair<std::int64_t, std::int64_t>;
using GridOutline = std::vector<GridPoint>;

// Rotated to start at its smallest point, direction kept.
GridOutline normalized(GridOutline o) {
    if (!o.empty()) std::rotate(o.begin(), std::min_element(o.begin(), o.end()), o.end());
    return o;
}

std::vector<GridOutline> sorted(std::vector<GridOutline> v) {
    for (auto& o : v) o = normalized(std::move(o));
    std::sort(v.begin(), v.end());
    return v;
}

// The caller's clean-up, as OpenSCAD's ClipperUtils::sanitize + toPolygon2d.
std::vector<GridOutline> sanitizeToGrid(const Outlines& shape) {
    ClipperLib::Paths paths;
    for (const Outline& o : shape.outlines) {
        ClipperLib::Path p;
        for (const auto& v : o.points) p.emplace_back(ClipperLib::IntPoint(v.x * 65536, v.y * 65536));
        if (!shape.sanitized && !ClipperLib::Orientation(p)) std::reverse(p.begin(), p.end());
        paths.push_back(p);
    }
    ClipperLib::Clipper clipper;
    clipper.AddPaths(paths, ClipperLib::ptSubject, true);
    ClipperLib::PolyTree tree;
    clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd);
    std::vector<GridOutline> out;
    for (const ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext()) {
        ClipperLib::Path cleaned;
        ClipperLib::CleanPolygon(node->Contour, cleaned);
        if (cleaned.size() < 3) continue;
        GridOutline o;
        // Back to units (/ 2^16) and on to the .scad's scale(65536): the grid integers.
        for (const auto& p : cleaned) {
            const double x = 1.0 * double(p.X) / 65536 * 65536, y = 1.0 * double(p.Y) / 65536 * 65536;
            o.emplace_back(std::int64_t(x), std::int64_t(y));
        }
        out.push_back(o);
    }
    return out;
}

// The outlines of OpenSCAD's SVG export: "M x,-y L x,-y ... z" per outline.
std::vector<GridOutline> readExport(const std::string& name) {
    std::ifstream in(kDir + name);
    EXPECT_TRUE(in.good()) << name;
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::size_t start = text.find("<path d=\"");
    std::vector<GridOutline> out;
    if (start == std::string::npos) return out;
    const std::size_t end = text.find('"', start + 9);
    std::istringstream d(text.substr(start + 9, end - start - 9));
    std::string token;
    GridOutline current;
    while (d >> token) {
        if (token == "M" || token == "L") continue;
        if (token == "z") {
            out.push_back(current);
            current.clear();
            continue;
        }
        const std::size_t comma = token.find(',');
        const double x = std::stod(token.substr(0, comma)), y = -std::stod(token.substr(comma + 1));
        EXPECT_EQ(x, std::floor(x)) << name << ": not on the grid: " << token;
        EXPECT_LT(std::fabs(x), 1e6) << name << ": printed with too few digits: " << token;
        EXPECT_LT(std::fabs(y), 1e6) << name << ": printed with too few digits: " << token;
        current.emplace_back(std::int64_t(x), std::int64_t(y));
    }
    return out;
}

// Twice the signed area: outer outlines count, holes subtract, whatever the partition.
std::int64_t twiceArea(const std::vector<GridOutline>& outlines) {
    std::int64_t sum = 0;
    for (const auto& o : outlines) {
        for (std::size_t i = 0; i < o.size(); ++i) {
            const auto& p = o[i];
            const auto& q = o[(i + 1) % o.size()];
            sum += p.first * q.second - q.first * p.second;
        }
    }
    return sum;
}

// Whether (x, y) lies inside the cleaned outlines (even-odd over all of them).
bool covers(const std::vector<GridOutline>& outlines, double x, double y) {
    bool in = false;
    for (const auto& o : outlines) {
        for (std::size_t i = 0, j = o.size() - 1; i < o.size(); j = i++) {
            const double xi = double(o[i].first), yi = double(o[i].second);
            const double xj = double(o[j].first), yj = double(o[j].second);
            if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
        }
    }
    return in;
}

scene::FlatImport flatImport(const std::string& file) {
    scene::FlatImport f;
    f.path = kDir + file;
    return f;
}

void expectSameOutlines(const scene::FlatImport& import, const std::string& exportName) {
    const std::vector<GridOutline> expected = sorted(readExport(exportName));
    ASSERT_FALSE(expected.empty()) << exportName;
    Outlines mine;
    ASSERT_NO_THROW(mine = importFlat(import)) << exportName;
    const std::vector<GridOutline> actual = sorted(sanitizeToGrid(mine));
    EXPECT_EQ(actual.size(), expected.size()) << exportName;
    std::size_t matching = 0;
    for (const auto& o : actual) matching += std::binary_search(expected.begin(), expected.end(), o) ? 1 : 0;
    EXPECT_EQ(matching, expected.size()) << exportName << ": outlines differ from OpenSCAD's";
    if (actual != expected) {
        for (std::size_t i = 0; i < std::max(actual.size(), expected.size()); ++i) {
            const std::size_t na = i < actual.size() ? actual[i].size() : 0;
            const std::size_t ne = i < expected.size() ? expected[i].size() : 0;
            ADD_FAILURE() << exportName << " outline " << i << ": " << na << " points, OpenSCAD " << ne
                          << (i < actual.size() && i < expected.size() && actual[i] == expected[i] ? " (same)" : "");
        }
    }
}

std::string tempFile(const std::string& name, const std::string& content) {
    const auto path = std::filesystem::temp_directory_path() / ("strata_import_" + name);
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
}

scene::FlatImport tempImport(const std::string& name, const std::string& content) {
    scene::FlatImport f;
    f.path = tempFile(name, content);
    return f;
}

std::string errorOf(const scene::FlatImport& import) {
    try {
        importFlat(import);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// DXF text from (code, value) pairs.
std::string dxf(const std::vector<std::pair<int, std::string>>& pairs) {
    std::string s;
    for (const auto& [code, value] : pairs) s += std::to_string(code) + "\n" + value + "\n";
    return s;
}

}  // namespace

// ---- DXF -----------------------------------------------------------------

TEST(ImportDxf, ShapesMatchOpenScad) {
    // LINEs joined out of order, CIRCLE, closed LWPOLYLINE (bulge ignored),
    // ARC + LINE, ELLIPSE, an open LWPOLYLINE; POLYLINE, SPLINE, TEXT ignored.
    expectSameOutlines(flatImport("shapes.dxf"), "dxf_shapes.svg");
}

TEST(ImportDxf, LayerFilter) {
    scene::FlatImport f = flatImport("shapes.dxf");
    f.layer = "marks";
    expectSameOutlines(f, "dxf_shapes_layer.svg");
}

TEST(ImportDxf, OriginScaleAndFn) {
    scene::FlatImport f = flatImport("shapes.dxf");
    f.origin = {3, -2};
    f.scale = 0.5;
    f.fragments.fn = 7;
    expectSameOutlines(f, "dxf_shapes_origin_scale.svg");
}

TEST(ImportDxf, FaAndFs) {
    scene::FlatImport f = flatImport("shapes.dxf");
    f.fragments.fa = 5;
    f.fragments.fs = 0.5;
    expectSameOutlines(f, "dxf_shapes_fa_fs.svg");
}

TEST(ImportDxf, BlocksAndInserts) { expectSameOutlines(flatImport("blocks.dxf"), "dxf_blocks.svg"); }

TEST(ImportDxf, BlocksScaled) {
    scene::FlatImport f = flatImport("blocks.dxf");
    f.origin = {1, 1};
    f.scale = 0.75;
    f.fragments.fn = 9;
    expectSameOutlines(f, "dxf_blocks_scaled.svg");
}

TEST(ImportDxf, TangleOfSharedEnds) {
    // Random segments on a lattice and a block inserted onto the same points:
    // which segments join into which paths, open or closed, decides the shape.
    // Where paths touch at a point, Clipper 6.4.2 (strata) and the 6.2.1 that
    // OpenSCAD 2021.01 bundles split the same region into outlines
    // differently, so the region is compared: its exact area and which of a
    // grid of points it covers. (With 6.2.1 the outlines are identical.)
    const std::vector<GridOutline> expected = readExport("dxf_tangle.svg");
    const std::vector<GridOutline> actual = sanitizeToGrid(importFlat(flatImport("tangle.dxf")));
    EXPECT_EQ(twiceArea(actual), twiceArea(expected));
    int differing = 0, inside = 0;
    for (int i = 0; i < 240; ++i) {
        for (int j = 0; j < 240; ++j) {
            // Points between the grid's lines: never on an edge.
            const double x = (-15.0 + 0.125 * i + 0.0123) * 65536, y = (-15.0 + 0.125 * j + 0.0371) * 65536;
            const bool a = covers(actual, x, y), e = covers(expected, x, y);
            differing += a != e;
            inside += e;
        }
    }
    EXPECT_GT(inside, 1000);
    EXPECT_EQ(differing, 0);
}

TEST(ImportDxf, StaleBlockEntriesCloseAChain) {
    // A chain whose ends meet a block's (uninserted) segment counts as closed
    // in 2021.01, drops its first point and vanishes.
    expectSameOutlines(flatImport("stale.dxf"), "dxf_stale.svg");
}

TEST(ImportDxf, OutlinesAreUnsanitized) {
    const Outlines o = importFlat(flatImport("shapes.dxf"));
    EXPECT_FALSE(o.sanitized);
    // The circle: 10 segments of r = 3 ($fa 12, $fs 2), one closed path of 10 points.
    bool found = false;
    for (const auto& outline : o.outlines) {
        if (outline.points.size() != 10) continue;
        bool onCircle = true;
        for (const auto& p : outline.points) onCircle &= std::fabs(std::hypot(p.x + 6, p.y - 2) - 3) < 1e-3;
        found |= onCircle;
    }
    EXPECT_TRUE(found);
}

TEST(ImportDxf, Errors) {
    EXPECT_NE(errorOf(flatImport("no_such_file.dxf")).find("import: cannot read"), std::string::npos);
    EXPECT_NE(errorOf(flatImport("garbage.dxf")).find("has no outlines"), std::string::npos);
    EXPECT_NE(errorOf(flatImport("empty.dxf")).find("has no outlines"), std::string::npos);
    scene::FlatImport layer = flatImport("shapes.dxf");
    layer.layer = "no such layer";
    EXPECT_NE(errorOf(layer).find("on layer 'no such layer'"), std::string::npos);
    EXPECT_THROW(importFlat(tempImport("empty_file.dxf", "")), Error);
    scene::FlatImport dir;
    dir.path = kDir;  // a directory, and not .dxf either
    EXPECT_THROW(importFlat(dir), Error);
    EXPECT_THROW(importFlat(tempImport("directory_named.txt", "0\nEOF\n")), Error);  // neither .dxf nor .svg
}

TEST(ImportDxf, HostileInputFailsCleanly) {
    const auto section = [](std::vector<std::pair<int, std::string>> entities) {
        std::vector<std::pair<int, std::string>> p{{0, "SECTION"}, {2, "ENTITIES"}};
        p.insert(p.end(), entities.begin(), entities.end());
        p.push_back({0, "ENDSEC"});
        p.push_back({0, "EOF"});
        return dxf(p);
    };
    const auto start = std::chrono::steady_clock::now();
    // A circle asking for 10^9 segments.
    scene::FlatImport many = tempImport("fn.dxf", section({{0, "CIRCLE"}, {10, "0"}, {20, "0"}, {40, "1"}}));
    many.fragments.fn = 1e9;
    EXPECT_NE(errorOf(many).find("segments"), std::string::npos);
    // $fn beyond int: 2021.01 (x86-64) converts it to INT_MIN and draws nothing.
    many.fragments.fn = 1e12;
    EXPECT_NE(errorOf(many).find("has no outlines"), std::string::npos);
    // An arc whose end angle lies 10^300 turns before its start.
    EXPECT_NE(
        errorOf(tempImport("arc.dxf", section({{0, "ARC"}, {10, "0"}, {20, "0"}, {40, "1"}, {50, "1e300"}, {51, "0"}})))
            .find("too far apart"),
        std::string::npos);
    // Curves that go round many times (found by the DXF fuzzer: an ELLIPSE
    // with an end parameter of 179586 traced one ellipse 28,582 times, and
    // Clipper then ran for minutes on it).
    const std::string ellipse = errorOf(tempImport(
        "ellipse.dxf", section({{0, "ELLIPSE"}, {10, "0"}, {20, "0"}, {11, "2.5"}, {21, "1"}, {40, "0.5"}, {41, "0"},
                                {42, "179586"}})));
    EXPECT_NE(ellipse.find("an ELLIPSE in the DXF file sweeps 28581.9"), std::string::npos) << ellipse;
    EXPECT_NE(errorOf(tempImport("arcs.dxf", section({{0, "ARC"}, {10, "0"}, {20, "0"}, {40, "1"}, {50, "0"},
                                                      {51, "7200"}})))
                  .find("an ARC in the DXF file sweeps 20.0"),
              std::string::npos);
    // 100,000 segments ending at one point: joining them into paths stays
    // linear in them (it once compared each with every other).
    {
        const std::vector<std::pair<int, std::string>> there{{0, "LINE"}, {10, "0"}, {20, "0"}, {11, "1"}, {21, "0"}};
        const std::vector<std::pair<int, std::string>> back{{0, "LINE"}, {10, "1"}, {20, "0"}, {11, "0"}, {21, "0"}};
        std::vector<std::pair<int, std::string>> lines;
        for (int i = 0; i < 50000; ++i) {
            lines.insert(lines.end(), there.begin(), there.end());
            lines.insert(lines.end(), back.begin(), back.end());
        }
        EXPECT_NO_THROW(importFlat(tempImport("star.dxf", section(lines))));
    }
    // A coordinate that overflows the grid.
    EXPECT_THROW(
        importFlat(tempImport("far.dxf", section({{0, "LINE"}, {10, "1e300"}, {20, "0"}, {11, "0"}, {21, "0"}}))),
        Error);
    EXPECT_THROW(
        importFlat(tempImport("nan.dxf", section({{0, "LINE"}, {10, "nan"}, {20, "0"}, {11, "0"}, {21, "0"}}))), Error);
    // A block that inserts itself doubles at every INSERT: refused past the cap.
    {
        std::vector<std::pair<int, std::string>> p{{0, "SECTION"}, {2, "BLOCKS"}, {0, "BLOCK"}, {2, "B"}, {0, "LINE"},
                                                   {10, "0"},      {20, "0"},     {11, "1"},    {21, "1"}};
        for (int i = 0; i < 40; ++i) {
            p.push_back({0, "INSERT"});
            p.push_back({2, "B"});
            p.push_back({10, "0.5"});
            p.push_back({20, "0"});
        }
        p.push_back({0, "ENDBLK"});
        p.push_back({0, "ENDSEC"});
        p.push_back({0, "EOF"});
        EXPECT_NE(errorOf(tempImport("doubling.dxf", dxf(p))).find("segments"), std::string::npos);
    }
    // Vertex counts that make dxflib allocate gigabytes mean nothing here.
    EXPECT_NO_THROW(importFlat(tempImport("counts.dxf", section({{0, "LWPOLYLINE"},
                                                                 {90, "2000000000"},
                                                                 {42, "1"},
                                                                 {10, "0"},
                                                                 {20, "0"},
                                                                 {10, "1"},
                                                                 {20, "0"},
                                                                 {10, "0"},
                                                                 {20, "1"},
                                                                 {70, "1"},
                                                                 {0, "SPLINE"},
                                                                 {72, "2000000000"},
                                                                 {73, "2000000000"}}))));
    // Binary junk.
    std::string junk;
    for (int i = 0; i < 4096; ++i) junk += static_cast<char>((i * 7919) % 251);
    EXPECT_THROW(importFlat(tempImport("junk.dxf", junk)), Error);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

TEST(ImportDxf, ManyOpenPathsStayFast) {
    // 20000 separate open segments: 2021.01's search restarts from the first
    // segment for each path; this must not be quadratic.
    std::vector<std::pair<int, std::string>> p{{0, "SECTION"}, {2, "ENTITIES"}};
    for (int i = 0; i < 20000; ++i) {
        const double x = (i % 200) * 0.1, y = (i / 200) * 0.1;
        p.push_back({0, "LINE"});
        p.push_back({10, std::to_string(x)});
        p.push_back({20, std::to_string(y)});
        p.push_back({11, std::to_string(x + 0.05)});
        p.push_back({21, std::to_string(y + 0.02)});
    }
    p.push_back({0, "ENDSEC"});
    p.push_back({0, "EOF"});
    const auto start = std::chrono::steady_clock::now();
    const Outlines o = importFlat(tempImport("open.dxf", dxf(p)));
    EXPECT_EQ(o.outlines.size(), 20000u);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

// ---- SVG -----------------------------------------------------------------

TEST(ImportSvg, DrawingMatchesOpenScad) {
    // rect (plain and rounded), circle, ellipse, polygon, polyline and line
    // strokes, paths with every command, nested transforms, defs skipped.
    expectSameOutlines(flatImport("drawing.svg"), "svg_drawing.svg");
}

TEST(ImportSvg, Center) {
    scene::FlatImport f = flatImport("drawing.svg");
    f.center = true;
    expectSameOutlines(f, "svg_drawing_center.svg");
}

TEST(ImportSvg, UnitlessSizeAtDpiAndAlignment) {
    expectSameOutlines(flatImport("units.svg"), "svg_units.svg");
    scene::FlatImport f = flatImport("units.svg");
    f.dpi = 96;
    expectSameOutlines(f, "svg_units_dpi96.svg");
}

TEST(ImportSvg, Slice) { expectSameOutlines(flatImport("slice.svg"), "svg_slice.svg"); }

TEST(ImportSvg, NoViewBoxMeansMillimetres) { expectSameOutlines(flatImport("noviewbox.svg"), "svg_noviewbox.svg"); }

TEST(ImportSvg, LessCommonStructure) {
    // symbol, use, clipPath, a 'z' before an open subpath, a nested svg.
    expectSameOutlines(flatImport("quirks.svg"), "svg_quirks.svg");
}

TEST(ImportSvg, ComesBackSanitized) {
    const Outlines o = importFlat(flatImport("drawing.svg"));
    EXPECT_TRUE(o.sanitized);
    for (const auto& outline : o.outlines) {
        for (const auto& p : outline.points) {
            EXPECT_EQ(p.x * 65536, std::floor(p.x * 65536));
            EXPECT_EQ(p.y * 65536, std::floor(p.y * 65536));
        }
    }
}

TEST(ImportSvg, SkewsBeyondAnIntsTurnsAreNoUndefinedConversion) {
    // Found by the SVG fuzzer: skewY(4e21) counted its half turns in an int
    // (undefined past 2^31; UBSan stopped there). They are converted as an
    // x86-64 build of OpenSCAD converts them; the angle means nothing, and
    // whatever the rectangle becomes, the reader either reads it or says why.
    // And an exponent of twenty digits (its value overflowed while read).
    for (const char* angle : {"4e21", "1e12", "-1e12", "4E44444444444444444444"}) {
        const std::string svg = std::string("<svg xmlns=\"http://www.w3.org/2000/svg\"><g transform=\"skewY(") + angle +
                                ")\"><rect width=\"2\" height=\"1\"/></g></svg>";
        try {
            importFlat(tempImport("skew.svg", svg));
        } catch (const Error&) {
        }
    }
}

TEST(ImportSvg, Errors) {
    EXPECT_NE(errorOf(flatImport("no_such_file.svg")).find("import: cannot read"), std::string::npos);
    EXPECT_NE(errorOf(flatImport("broken.svg")).find("cannot parse"), std::string::npos);
    EXPECT_NE(errorOf(flatImport("empty.svg")).find("has no outlines"), std::string::npos);
    EXPECT_THROW(importFlat(tempImport("empty_file.svg", "")), Error);
    EXPECT_THROW(importFlat(tempImport("truncated.svg",
                                       "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"1\" height=\"1\"/>")),
                 Error);
    EXPECT_THROW(
        importFlat(tempImport("huge.svg",
                              "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"1e300\" height=\"1\"/></svg>")),
        Error);
    // Entity expansion is limited by libxml2 (no billion laughs).
    std::string laughs = "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY a \"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\">";
    std::string prev = "a";
    for (int i = 0; i < 12; ++i) {
        std::string name = "e";  // appended, not "e" + ...: GCC 12 warns of a false overlap there (-Wrestrict)
        name += std::to_string(i);
        laughs += "<!ENTITY " + name + " \"";
        for (int k = 0; k < 16; ++k) laughs += "&" + prev + ";";
        laughs += "\">";
        prev = name;
    }
    laughs +=
        "]><svg xmlns=\"http://www.w3.org/2000/svg\"><text>&" + prev + ";</text><rect width=\"1\" height=\"1\"/></svg>";
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(importFlat(tempImport("laughs.svg", laughs)), Error);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(ImportSvg, ExternalEntitiesAreNotLoaded) {
    // An entity naming a FIFO nobody writes to would block the reader forever.
    const auto fifo = std::filesystem::temp_directory_path() / "strata_import_fifo";
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string svg = "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY x SYSTEM \"" + fifo.string() +
                            "\">]><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10mm\" height=\"10mm\" "
                            "viewBox=\"0 0 10 10\"><text>&x;</text><rect width=\"2\" height=\"3\"/></svg>";
    const auto start = std::chrono::steady_clock::now();
    try {
        const Outlines o = importFlat(tempImport("external.svg", svg));
        EXPECT_EQ(o.outlines.size(), 1u);
    } catch (const Error&) {
        // Refusing the entity may also end the parse: either way, no hang.
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    std::filesystem::remove(fifo);
}
