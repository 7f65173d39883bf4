#include "strata/flat/Text.h"

#include <gtest/gtest.h>
#include <fontconfig/fontconfig.h>
#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "strata/core/Error.h"

// text() against OpenSCAD 2021.01's own output: tests/data/flat/text/ holds
// each case exported by OpenSCAD as DXF at 65536 times its size, shifted so
// that every point of the Clipper grid is an exact integer (README.md there).
// The glyphs are unioned here as OpenSCAD's GeometryEvaluator does for a
// TextNode (ClipperUtils::apply(..., ctUnion)), and every vertex must match.

using namespace strata;
using namespace strata::flat;

namespace {

constexpr double kClipperScale = 65536.0;

// One edge of an outline, as DXF's LINE entities list them, in grid units.
struct Line {
    long long x1, y1, x2, y2;
    bool operator==(const Line&) const = default;
};

std::ostream& operator<<(std::ostream& os, const Line& l) {
    return os << "(" << l.x1 << ", " << l.y1 << ") -> (" << l.x2 << ", " << l.y2 << ")";
}

std::string dataPath(const std::string& name) { return std::string(STRATA_TEST_DIR) + "/data/flat/text/" + name; }

// fonts/StrataCubicTest.otf (CFF outlines: cubic Beziers) is found as OpenSCAD
// found it for the reference, through OPENSCAD_FONT_PATH, which the font
// library reads when it first starts: set before main().
const bool kCubicFontPathSet = [] {
    const std::string dir = dataPath("fonts");
    const char* old = std::getenv("OPENSCAD_FONT_PATH");
    const std::string value = old && *old ? dir + ":" + old : dir;
    return ::setenv("OPENSCAD_FONT_PATH", value.c_str(), 1) == 0;
}();

struct Case {
    long long shiftX = 0, shiftY = 0;
    std::size_t vertices = 0;
};

Case readCase(const std::string& name) {
    std::ifstream in(dataPath("cases.txt"));
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        std::string n;
        Case c;
        ls >> n >> c.shiftX >> c.shiftY >> c.vertices;
        if (n == name) return c;
    }
    ADD_FAILURE() << "no case " << name << " in cases.txt";
    return {};
}

// The LINE entities of OpenSCAD's DXF export, moved back by the case's shift.
std::vector<Line> readDxf(const std::string& name, const Case& c) {
    std::ifstream in(dataPath(name + ".dxf"));
    EXPECT_TRUE(in) << "cannot read " << name << ".dxf";
    std::vector<std::string> rows;
    std::string row;
    while (std::getline(in, row)) rows.push_back(row);
    std::vector<Line> lines;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i] != "LINE") continue;
        double v[4] = {0, 0, 0, 0};
        int found = 0;
        for (std::size_t j = i + 1; j + 1 < rows.size() && rows[j] != "  0"; j += 2) {
            const std::string code = rows[j];
            const int k = code == " 10" ? 0 : code == " 20" ? 1 : code == " 11" ? 2 : code == " 21" ? 3 : -1;
            if (k >= 0) {
                v[k] = std::stod(rows[j + 1]);
                ++found;
            }
        }
        EXPECT_EQ(found, 4);
        for (double d : v) EXPECT_EQ(d, std::trunc(d)) << "the reference is not on the grid";
        lines.push_back({static_cast<long long>(v[0]) - c.shiftX, static_cast<long long>(v[1]) - c.shiftY,
                         static_cast<long long>(v[2]) - c.shiftX, static_cast<long long>(v[3]) - c.shiftY});
    }
    return lines;
}

ClipperLib::Path toPath(const Outline& o, bool keepOrientation) {
    ClipperLib::Path p;
    for (const glm::dvec2& v : o.points) p.emplace_back(v.x * kClipperScale, v.y * kClipperScale);
    if (!keepOrientation && !ClipperLib::Orientation(p)) std::reverse(p.begin(), p.end());
    return p;
}

// ClipperUtils::toPolygon2d: the tree's outlines in GetNext order, cleaned.
std::vector<ClipperLib::Path> fromTree(const ClipperLib::PolyTree& tree) {
    std::vector<ClipperLib::Path> out;
    for (const ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext()) {
        ClipperLib::Path cleaned;
        ClipperLib::CleanPolygon(node->Contour, cleaned);
        if (cleaned.size() >= 3) out.push_back(cleaned);
    }
    return out;
}

// ClipperUtils::apply(polygons, ctUnion) over the glyphs, as
// GeometryEvaluator::visit(TextNode) calls it. A glyph marked sanitized (as
// OpenSCAD 2021.01's DrawingCallback marks every glyph) goes in as it is, its
// orientation kept; an unsanitized one is first made to point up and unioned
// even-odd. `forceEvenOdd` treats every glyph as unsanitized.
std::vector<ClipperLib::Path> unionGlyphs(const std::vector<Outlines>& glyphs, bool forceEvenOdd = false) {
    ClipperLib::Clipper clipper;
    bool first = true;
    for (const Outlines& g : glyphs) {
        const bool sanitized = g.sanitized && !forceEvenOdd;
        ClipperLib::Paths paths;
        for (const Outline& o : g.outlines) paths.push_back(toPath(o, sanitized));
        if (!sanitized) {
            ClipperLib::Clipper even;
            even.AddPaths(paths, ClipperLib::ptSubject, true);
            ClipperLib::PolyTree tree;
            even.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd);
            ClipperLib::PolyTreeToPaths(tree, paths);
        }
        clipper.AddPaths(paths, first ? ClipperLib::ptSubject : ClipperLib::ptClip, true);
        first = false;
    }
    ClipperLib::PolyTree result;
    clipper.Execute(ClipperLib::ctUnion, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return fromTree(result);
}

std::vector<Line> toLines(const std::vector<ClipperLib::Path>& paths) {
    std::vector<Line> lines;
    for (const ClipperLib::Path& p : paths) {
        for (std::size_t i = 0; i < p.size(); ++i) {
            const ClipperLib::IntPoint& a = p[i];
            const ClipperLib::IntPoint& b = p[(i + 1) % p.size()];
            lines.push_back({a.X, a.Y, b.X, b.Y});
        }
    }
    return lines;
}

void expectSameLines(const std::vector<Line>& mine, const std::vector<Line>& reference, const std::string& what) {
    ASSERT_EQ(mine.size(), reference.size()) << what << ": vertex count";
    std::size_t differ = 0;
    for (std::size_t i = 0; i < mine.size(); ++i) {
        if (!(mine[i] == reference[i])) {
            if (differ < 5) ADD_FAILURE() << what << ": edge " << i << " is " << mine[i] << ", OpenSCAD " << reference[i];
            ++differ;
        }
    }
    EXPECT_EQ(differ, 0u) << what << ": edges that differ";
}

scene::Text makeText(const std::string& s) {
    scene::Text t;
    t.text = s;
    return t;
}

// Unions the glyphs as OpenSCAD does and compares every edge with its export.
void expectMatchesOpenScad(const std::string& name, const scene::Text& text) {
    SCOPED_TRACE(name);
    const Case c = readCase(name);
    const std::vector<Line> reference = readDxf(name, c);
    ASSERT_EQ(reference.size(), c.vertices);
    const std::vector<Outlines> glyphs = textGlyphs(text);
    for (const Outlines& g : glyphs) EXPECT_TRUE(g.sanitized) << "OpenSCAD marks its glyphs sanitized";
    expectSameLines(toLines(unionGlyphs(glyphs)), reference, name);
}

std::size_t vertexCount(const std::vector<ClipperLib::Path>& paths) {
    std::size_t n = 0;
    for (const auto& p : paths) n += p.size();
    return n;
}

}  // namespace

TEST(Text, EmptyTextGivesNoGlyphs) {
    EXPECT_TRUE(textGlyphs(makeText("")).empty());
    // A space has no outline: OpenSCAD drops such glyphs.
    EXPECT_TRUE(textGlyphs(makeText("   ")).empty());
}

TEST(Text, LetterOVertexCount) {
    // OpenSCAD 2021.01 makes text("o") of two outlines, 28 + 32 = 60 vertices
    // after the union (o.dxf): 4 steps per Bezier segment at the default size.
    const std::vector<Outlines> glyphs = textGlyphs(makeText("o"));
    ASSERT_EQ(glyphs.size(), 1u);
    EXPECT_EQ(glyphs[0].outlines.size(), 2u);
    const std::vector<ClipperLib::Path> u = unionGlyphs(glyphs);
    ASSERT_EQ(u.size(), 2u);
    EXPECT_EQ(u[0].size(), 28u);
    EXPECT_EQ(u[1].size(), 32u);
    EXPECT_EQ(vertexCount(u), 60u);
    EXPECT_EQ(readCase("o").vertices, 60u);
}

TEST(Text, GlyphsAreUnionedAsSanitizedNotEvenOdd) {
    // OpenSCAD's DrawingCallback marks each glyph sanitized, so Clipper sees
    // the raw contours (non-zero union). An even-odd pass per glyph would cut
    // the overlap of a composite's parts out of these accented letters
    // (and reorder the outlines of others): OpenSCAD does not do that.
    scene::Text t = makeText("\u00c5\u00c7\u00f8\u00e9");
    t.size = 6;
    const std::vector<Outlines> glyphs = textGlyphs(t);
    const std::vector<Line> reference = readDxf("accents", readCase("accents"));
    EXPECT_EQ(toLines(unionGlyphs(glyphs)), reference);
    EXPECT_NE(toLines(unionGlyphs(glyphs, true)), reference);
}

TEST(Text, OneGlyphPerInkedCharacter) {
    const std::vector<Outlines> glyphs = textGlyphs(makeText("a b"));
    EXPECT_EQ(glyphs.size(), 2u);
    for (const Outlines& g : glyphs) {
        EXPECT_TRUE(g.sanitized);
        for (const Outline& o : g.outlines) EXPECT_GE(o.points.size(), 3u);
    }
}

TEST(Text, UnparsableFontNameThrows) {
    // fontconfig cannot parse these patterns (OpenSCAD 2021.01 crashes on them).
    for (const char* font : {"Foo:weight=abc", "Liberation Sans:size=abc"}) {
        scene::Text t = makeText("A");
        t.font = font;
        try {
            textGlyphs(t);
            ADD_FAILURE() << "no error for font " << font;
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(font), std::string::npos) << what;
            EXPECT_EQ(what.rfind("text(): ", 0), 0u) << "no position, the caller adds it: " << what;
        }
    }
    // Empty text needs no font at all.
    scene::Text t = makeText("");
    t.font = "Foo:weight=abc";
    EXPECT_TRUE(textGlyphs(t).empty());
}

TEST(Text, AbsurdFragmentCountThrows) {
    scene::Text t = makeText("o");
    t.fragments.fn = 1e9;  // 125 million steps per curve
    EXPECT_THROW(textGlyphs(t), Error);
}

TEST(Text, MatchesOpenScadDefault) { expectMatchesOpenScad("o", makeText("o")); }

TEST(Text, MatchesOpenScadSizeSpacingCentered) {
    scene::Text t = makeText("Hg");
    t.size = 7;
    t.spacing = 1.3;
    t.halign = "center";
    t.valign = "center";
    expectMatchesOpenScad("hg_center", t);
}

TEST(Text, MatchesOpenScadSerifBold) {
    scene::Text t = makeText("Rag");
    t.font = "Liberation Serif:style=Bold";
    expectMatchesOpenScad("serif_bold", t);
}

TEST(Text, MatchesOpenScadTopToBottom) {
    scene::Text t = makeText("ABC");
    t.size = 5;
    t.direction = "ttb";
    expectMatchesOpenScad("ttb", t);
}

TEST(Text, MatchesOpenScadBottomToTopCentered) {
    scene::Text t = makeText("Hi");
    t.size = 6;
    t.direction = "btt";
    t.halign = "center";
    t.valign = "center";
    expectMatchesOpenScad("btt_center", t);
}

TEST(Text, MatchesOpenScadKerning) {
    scene::Text t = makeText("AVAT");
    t.size = 8;
    expectMatchesOpenScad("kerning", t);
}

TEST(Text, MatchesOpenScadFixedFragments) {
    scene::Text t = makeText("S");
    t.size = 4;
    t.fragments.fn = 40;  // 40 / 8 + 1 = 6 steps per segment
    expectMatchesOpenScad("fn40", t);
}

TEST(Text, MatchesOpenScadAngleAndSizeFragments) {
    scene::Text t = makeText("e");
    t.size = 20;
    t.fragments.fa = 5;
    t.fragments.fs = 0.5;  // min(72, 251) = 72 fragments: 10 steps
    expectMatchesOpenScad("fa_fs", t);
}

TEST(Text, MatchesOpenScadAccentedComposites) {
    scene::Text t = makeText("\u00c5\u00c7\u00f8\u00e9");
    t.size = 6;
    expectMatchesOpenScad("accents", t);
}

TEST(Text, MatchesOpenScadMonoRightBottom) {
    scene::Text t = makeText("Mono#1");
    t.size = 4;
    t.font = "Liberation Mono";
    t.halign = "right";
    t.valign = "bottom";
    expectMatchesOpenScad("mono_right_bottom", t);
}

TEST(Text, MatchesOpenScadSpace) { expectMatchesOpenScad("space", makeText("a b")); }

TEST(Text, MatchesOpenScadHebrewRightToLeft) {
    scene::Text t = makeText("\u05e9\u05dc\u05d5\u05dd");
    t.size = 6;
    t.direction = "rtl";
    t.language = "he";
    t.script = "Hebr";
    expectMatchesOpenScad("hebrew_rtl", t);
}

TEST(Text, MatchesOpenScadUnknownFontFallsBack) {
    // fontconfig answers an unknown family with its best match (no error, no
    // warning in OpenSCAD 2021.01); the reference was made where that is DejaVu Sans.
    std::string family;
    FcConfig* config = FcInitLoadConfigAndFonts();  // its own: the default one is never freed
    FcPattern* pattern = config ? FcNameParse(reinterpret_cast<const FcChar8*>("NoSuchFont Foo")) : nullptr;
    if (pattern) {
        FcConfigSubstitute(config, pattern, FcMatchPattern);
        FcDefaultSubstitute(pattern);
        FcResult result;
        if (FcPattern* match = FcFontMatch(config, pattern, &result)) {
            FcChar8* name = nullptr;
            if (FcPatternGetString(match, FC_FAMILY, 0, &name) == FcResultMatch) family = reinterpret_cast<char*>(name);
            FcPatternDestroy(match);
        }
        FcPatternDestroy(pattern);
    }
    if (config) FcConfigDestroy(config);
    if (family != "DejaVu Sans") GTEST_SKIP() << "fontconfig falls back to '" << family << "' here, not DejaVu Sans";
    scene::Text t = makeText("Fb");
    t.font = "NoSuchFont Foo";
    expectMatchesOpenScad("fallback", t);
}

TEST(Text, MatchesOpenScadBoldItalicTopRight) {
    scene::Text t = makeText("fig");
    t.size = 9;
    t.font = "Liberation Sans:style=Bold Italic";
    t.valign = "top";
    t.halign = "right";
    expectMatchesOpenScad("bold_italic_top", t);
}

TEST(Text, MatchesOpenScadOverlappingGlyphs) {
    scene::Text t = makeText("OOO");
    t.size = 6;
    t.spacing = 0.5;
    expectMatchesOpenScad("overlap", t);
}

TEST(Text, MatchesOpenScadCubicCurves) {
    ASSERT_TRUE(kCubicFontPathSet);
    scene::Text t = makeText("ODS");
    t.size = 6;
    t.font = "Strata Cubic Test";
    expectMatchesOpenScad("cubic", t);
}

TEST(Text, MatchesOpenScadCubicCurvesSevenSteps) {
    scene::Text t = makeText("SO");
    t.size = 5;
    t.font = "Strata Cubic Test";
    t.fragments.fn = 48;  // 48 / 8 + 1 = 7 steps: t = k/7 is inexact
    expectMatchesOpenScad("cubic_fn48", t);
}

TEST(Text, MatchesOpenScadCubicCurvesThreeSteps) {
    scene::Text t = makeText("DO");
    t.size = 5;
    t.font = "Strata Cubic Test";
    t.fragments.fn = 20;  // 3 steps
    t.halign = "center";
    expectMatchesOpenScad("cubic_fn20", t);
}

TEST(Text, ScriptAndDirectionAreDetectedWhenNotGiven) {
    // OpenSCAD detects an empty script / direction from the text itself.
    scene::Text given = makeText("\u05e9\u05dc\u05d5\u05dd");
    given.size = 6;
    given.direction = "rtl";
    given.language = "he";
    given.script = "Hebr";
    scene::Text detected = given;
    detected.direction = "";
    detected.script = "";
    const auto a = unionGlyphs(textGlyphs(given));
    const auto b = unionGlyphs(textGlyphs(detected));
    EXPECT_EQ(toLines(a), toLines(b));
}

TEST(Text, AlignmentShiftsTheWholeText) {
    scene::Text left = makeText("Ab");
    scene::Text right = left;
    right.halign = "right";
    const auto a = textGlyphs(left);
    const auto b = textGlyphs(right);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    const double dx = b[0].outlines[0].points[0].x - a[0].outlines[0].points[0].x;
    EXPECT_LT(dx, -10.0);
    for (std::size_t g = 0; g < a.size(); ++g) {
        for (std::size_t o = 0; o < a[g].outlines.size(); ++o) {
            for (std::size_t i = 0; i < a[g].outlines[o].points.size(); ++i) {
                EXPECT_NEAR(b[g].outlines[o].points[i].x - a[g].outlines[o].points[i].x, dx, 1e-9);
                EXPECT_DOUBLE_EQ(b[g].outlines[o].points[i].y, a[g].outlines[o].points[i].y);
            }
        }
    }
}

TEST(Text, WorkerThreadsAgree) {
    const std::vector<Line> expected = toLines(unionGlyphs(textGlyphs(makeText("Thread"))));
    std::vector<std::vector<Line>> got(4);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < got.size(); ++i) {
        threads.emplace_back([&got, i] {
            scene::Text t = makeText("Thread");
            if (i % 2) t.font = "Liberation Serif";  // another face at the same time
            for (int k = 0; k < 3; ++k) {
                auto lines = toLines(unionGlyphs(textGlyphs(t)));
                if (i % 2 == 0) got[i] = std::move(lines);
            }
        });
    }
    for (auto& t : threads) t.join();
    for (std::size_t i = 0; i < got.size(); i += 2) EXPECT_EQ(got[i], expected);
}
