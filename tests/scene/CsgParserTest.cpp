#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "NestedText.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using namespace strata::scene;

namespace {

Tree parse(const std::string& text, const std::string& baseDir = "") {
    std::istringstream in(text);
    return parseCsg(in, "t.csg", baseDir);
}

// The message of the strata::Error that parsing `text` throws, or "" if none.
std::string errorOf(const std::string& text, const std::string& baseDir = "") {
    try {
        parse(text, baseDir);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

const Node& rootNode(const Tree& t) { return t.nodes.at(static_cast<std::size_t>(t.root)); }
const Node& child(const Tree& t, const Node& n, std::size_t i) {
    return t.nodes.at(static_cast<std::size_t>(n.children.at(i)));
}
const Leaf& leafOf(const Tree& t, const Node& n) {
    EXPECT_EQ(n.kind, NodeKind::Leaf);
    return t.leaves.at(static_cast<std::size_t>(n.leaf));
}

}  // namespace

TEST(CsgParser, TopLevelIsAnImplicitUnion) {
    Tree t = parse("cube(size = [1, 2, 3], center = false);\nsphere($fn = 0, $fa = 12, $fs = 2, r = 1);\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    const Node& r = rootNode(t);
    EXPECT_EQ(r.kind, NodeKind::Union);
    ASSERT_EQ(r.children.size(), 2u);
    const Cube& c = std::get<Cube>(leafOf(t, child(t, r, 0)).primitive);
    EXPECT_EQ(c.size, glm::dvec3(1, 2, 3));
    EXPECT_FALSE(c.center);
    const Sphere& s = std::get<Sphere>(leafOf(t, child(t, r, 1)).primitive);
    EXPECT_EQ(s.r, 1.0);
    EXPECT_EQ(s.fragments.fa, 12.0);
    EXPECT_EQ(s.fragments.fs, 2.0);
    EXPECT_EQ(s.fragments.fn, 0.0);
}

TEST(CsgParser, SingleTopLevelStatementIsTheRoot) {
    Tree t = parse("difference() {\n\tcube(size = [10, 10, 10], center = true);\n\tsphere(r = 6);\n}\n");
    const Node& r = rootNode(t);
    EXPECT_EQ(r.kind, NodeKind::Difference);
    ASSERT_EQ(r.children.size(), 2u);
    EXPECT_EQ(r.where.line, 1);
    EXPECT_EQ(leafOf(t, child(t, r, 1)).where.line, 3);
    EXPECT_EQ(leafOf(t, child(t, r, 1)).where.column, 2);
}

TEST(CsgParser, MultmatrixIsRowMajorAndComposesOutsideIn) {
    Tree t = parse(
        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tmultmatrix([[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]) {\n"
        "\t\tcube(size = [1, 1, 1], center = false);\n\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const glm::dmat4& m = t.leaves[0].transform;
    // translate(5,0,0) * scale(2): the point (1,1,1) goes to (7,2,2).
    glm::dvec4 p = m * glm::dvec4(1, 1, 1, 1);
    EXPECT_EQ(p, glm::dvec4(7, 2, 2, 1));
    // The collapsed single-child groups leave the leaf as the root.
    EXPECT_EQ(rootNode(t).kind, NodeKind::Leaf);
}

TEST(CsgParser, OutermostColorWinsAndMinusOneIsUnset) {
    Tree t = parse(
        "color([0, 0, 1, 1]) {\n\tcolor([1, 0, 0, 1]) {\n\t\tsphere(r = 1);\n\t}\n}\n"
        "color([-1, -1, -1, 0.5]) {\n\tcolor([0, 1, 0, 1]) {\n\t\tcube(size = [1, 1, 1]);\n\t}\n}\n"
        "cube(size = 2);\n");
    ASSERT_EQ(t.leaves.size(), 3u);
    ASSERT_TRUE(t.leaves[0].color.has_value());
    EXPECT_EQ(*t.leaves[0].color, glm::dvec4(0, 0, 1, 1));
    // Outer node sets only alpha; the inner one fills in the rgb it left unset.
    ASSERT_TRUE(t.leaves[1].color.has_value());
    EXPECT_EQ(*t.leaves[1].color, glm::dvec4(0, 1, 0, 0.5));
    EXPECT_FALSE(t.leaves[2].color.has_value());
    EXPECT_EQ(std::get<Cube>(t.leaves[2].primitive).size, glm::dvec3(2, 2, 2));
}

TEST(CsgParser, ModifiersAtColumnZeroBeforeTheTabs) {
    Tree t = parse(
        "difference() {\n"
        "\tcube(size = [10, 10, 10], center = false);\n"
        "#\tmultmatrix([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1]]) {\n"
        "\t\tsphere($fn = 0, $fa = 12, $fs = 2, r = 2);\n"
        "\t}\n"
        "%\tcylinder($fn = 0, $fa = 12, $fs = 2, h = 20, r1 = 1, r2 = 1, center = false);\n"
        "}\n");
    const Node& r = rootNode(t);
    ASSERT_EQ(r.kind, NodeKind::Difference);
    ASSERT_EQ(r.children.size(), 2u);  // the '%' cylinder is not in the CSG
    const Leaf& sphere = leafOf(t, child(t, r, 1));
    EXPECT_EQ(sphere.display, Display::Highlight);
    EXPECT_EQ(sphere.where.line, 4);
    ASSERT_EQ(t.background.size(), 1u);
    const Leaf& cyl = leafOf(t, t.nodes[static_cast<std::size_t>(t.background[0])]);
    EXPECT_EQ(cyl.display, Display::Background);
    EXPECT_EQ(cyl.where.line, 6);
    EXPECT_EQ(cyl.where.column, 3);
}

TEST(CsgParser, RootModifierKeepsOnlyItsSubtreeWithoutAncestorTransforms) {
    Tree t = parse(
        "sphere(r = 1);\n"
        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "!\tcube(size = [1, 1, 1]);\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Cube>(t.leaves[0].primitive));
    EXPECT_EQ(t.leaves[0].transform, glm::dmat4(1.0));
    EXPECT_EQ(rootNode(t).kind, NodeKind::Leaf);
}

TEST(CsgParser, DisableModifierDropsTheSubtree) {
    Tree t = parse("*cube(size = 1);\nsphere(r = 1);\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Sphere>(t.leaves[0].primitive));
}

TEST(CsgParser, RenderAndGroupKeepTheirSubtree) {
    Tree t = parse(
        "render(convexity = 2) {\n\tgroup() {\n\t\tcube(size = 1);\n\t\tsphere(r = 2);\n\t}\n}\ngroup();\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    const Node& r = rootNode(t);
    ASSERT_EQ(r.kind, NodeKind::Union);
    // the render/group pair collapses; the empty group stays an empty union
    ASSERT_EQ(r.children.size(), 2u);
    EXPECT_EQ(child(t, r, 0).kind, NodeKind::Union);
    EXPECT_EQ(child(t, r, 0).children.size(), 2u);
    EXPECT_EQ(child(t, r, 1).kind, NodeKind::Union);
    EXPECT_TRUE(child(t, r, 1).children.empty());
}

TEST(CsgParser, CylinderConeAndDefaults) {
    Tree t = parse("cylinder($fn = 7, $fa = 12, $fs = 2, h = 3, r1 = 1, r2 = 0, center = true);\n"
                   "cylinder(h = 2, r = 4);\ncylinder(h = 2, d1 = 4, d2 = 2);\n");
    ASSERT_EQ(t.leaves.size(), 3u);
    const auto& a = std::get<Cylinder>(t.leaves[0].primitive);
    EXPECT_EQ(a.h, 3.0);
    EXPECT_EQ(a.r1, 1.0);
    EXPECT_EQ(a.r2, 0.0);
    EXPECT_TRUE(a.center);
    EXPECT_EQ(a.fragments.fn, 7.0);
    const auto& b = std::get<Cylinder>(t.leaves[1].primitive);
    EXPECT_EQ(b.r1, 4.0);
    EXPECT_EQ(b.r2, 4.0);
    const auto& c = std::get<Cylinder>(t.leaves[2].primitive);
    EXPECT_EQ(c.r1, 2.0);
    EXPECT_EQ(c.r2, 1.0);
}

TEST(CsgParser, PolyhedronPointsAndFaces) {
    Tree t = parse("polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], "
                   "faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]], convexity = 1);\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const auto& p = std::get<Polyhedron>(t.leaves[0].primitive);
    ASSERT_EQ(p.points.size(), 4u);
    EXPECT_EQ(p.points[3], glm::dvec3(0, 0, 1));
    ASSERT_EQ(p.faces.size(), 4u);
    EXPECT_EQ(p.faces[1], (std::vector<int>{0, 3, 1}));
}

TEST(CsgParser, NumbersInAllTheirForms) {
    Tree t = parse("multmatrix([[1e-7, 0, 0, .5], [0, 1e+20, 0, -2.5E1], [0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = 1); }");
    const glm::dmat4& m = t.leaves.at(0).transform;
    EXPECT_EQ(m[0][0], 1e-7);
    EXPECT_EQ(m[1][1], 1e20);
    EXPECT_EQ(m[3][0], 0.5);
    EXPECT_EQ(m[3][1], -25.0);
}

TEST(CsgParser, BracelessChildStatements) {
    Tree t = parse("multmatrix([[1, 0, 0, 3], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                   "difference() { cube(size = 2); sphere(r = 1); }\nsphere(r = 5);");
    ASSERT_EQ(t.leaves.size(), 3u);
    EXPECT_EQ(t.leaves[0].transform[3][0], 3.0);
    EXPECT_EQ(t.leaves[2].transform[3][0], 0.0);
    const Node& r = rootNode(t);
    ASSERT_EQ(r.children.size(), 2u);
    EXPECT_EQ(child(t, r, 0).kind, NodeKind::Difference);
}

TEST(CsgParser, UnsupportedNodesWarnOncePerTypeAndAreCounted) {
    Tree t = parse(
        "roof(method = \"straight\", convexity = 1) {\n"
        "\tcube(size = [2, 2, 2], center = false);\n\tsphere(r = 1);\n}\n"
        "render(convexity = 1) {\n\tfill() {\n\t\tcircle(r = 1);\n\t}\n}\n"
        "roof() { cube(size = 1); cylinder(r = 1); }\n"
        "cube(size = 1);\n");
    ASSERT_EQ(t.leaves.size(), 1u);  // only the cube; the fill's circle is left out
    EXPECT_EQ(t.unsupported.at("roof"), 2);
    EXPECT_EQ(t.unsupported.at("fill"), 1);
    EXPECT_EQ(t.unsupported.count("circle"), 0u);  // inside a left-out subtree: not looked at
    ASSERT_EQ(t.warnings.size(), 2u);
    EXPECT_EQ(t.warnings[0].message.rfind("t.csg:1:1: warning: 'roof'", 0), 0u) << t.warnings[0].message;
    EXPECT_EQ(t.warnings[1].message.rfind("t.csg:6:2: warning: 'fill'", 0), 0u) << t.warnings[1].message;
}

TEST(CsgParser, AbsurdFnIsClampedWithAWarning) {
    Tree t = parse("sphere($fn = 1e9, r = 1);");
    EXPECT_EQ(std::get<Sphere>(t.leaves.at(0).primitive).fragments.fn, 1024.0);
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_NE(t.warnings[0].message.find("clamped"), std::string::npos);
}

TEST(CsgParser, CommentsAreSkipped) {
    Tree t = parse("// a comment\n/* block\n comment */ cube(size = 1); // trailing\n");
    EXPECT_EQ(t.leaves.size(), 1u);
}

TEST(CsgParser, ImportResolvesRelativeToTheCsgFile) {
    auto dir = std::filesystem::temp_directory_path() / "strata_import_test";
    std::filesystem::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "part.stl") << "solid x\nendsolid x\n";
    Tree t = parse("import(file = \"sub/part.stl\", layer = \"\", origin = [0, 0], scale = 1, convexity = 1, "
                   "$fn = 0, $fa = 12, $fs = 2, timestamp = 1);",
                   dir.string());
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_EQ(std::get<Import>(t.leaves[0].primitive).path, (dir / "sub" / "part.stl").string());
    // A 2D format outside an extrusion is a flat shape, shown as a slab.
    std::ofstream(dir / "drawing.dxf") << "0\nEOF\n";
    Tree t2 = parse("import(file = \"drawing.dxf\");", dir.string());
    ASSERT_EQ(t2.leaves.size(), 1u);
    const FlatTree& shape = std::get<FlatSlab>(t2.leaves[0].primitive).shape;
    ASSERT_EQ(shape.shapes.size(), 1u);
    EXPECT_EQ(std::get<FlatImport>(shape.shapes[0]).path, (dir / "drawing.dxf").string());
    EXPECT_TRUE(t2.warnings.empty());
    std::filesystem::remove_all(dir);
}

TEST(CsgParser, EmptyPolyhedronAndEmptyImportAreLeftOutWithWarnings) {
    // Both appear in OpenSCAD's own dumps (tests/regression/dumptest/allmodules).
    Tree t = parse("polyhedron(points = [], faces = [], convexity = 1);\n"
                   "import(file = \"\", layer = \"\", origin = [0, 0], scale = 1, convexity = 1, $fn = 0, $fa = 12, "
                   "$fs = 2, timestamp = 0);\ncube(size = 1);\n");
    EXPECT_EQ(t.leaves.size(), 1u);
    EXPECT_EQ(t.warnings.size(), 2u);
}

TEST(CsgParser, ModulesWithoutChildrenAreEmpty) {
    Tree t = parse("group();\nintersection();\ndifference();\nmultmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]);\n"
                   "color([-1, -1, -1, 1]);\nrender(convexity = 1);\n");
    EXPECT_TRUE(t.leaves.empty());
    const Node& r = rootNode(t);
    ASSERT_EQ(r.children.size(), 6u);
    EXPECT_EQ(child(t, r, 1).kind, NodeKind::Intersection);
    EXPECT_EQ(child(t, r, 2).kind, NodeKind::Difference);
    for (int c : r.children) EXPECT_TRUE(t.nodes[static_cast<std::size_t>(c)].children.empty());
}

// ---- bad input: one message, starting with file:line:col ----

struct BadInput {
    const char* name;
    const char* text;
    const char* where;    // expected "file:line:col" prefix
    const char* message;  // expected part of the message
};

class CsgParserBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CsgParserBadInput, FailsWithFileLineAndColumn) {
    const BadInput& b = GetParam();
    std::string e = errorOf(b.text);
    ASSERT_FALSE(e.empty()) << "no error for " << b.name;
    EXPECT_EQ(e.rfind(std::string(b.where) + ": ", 0), 0u) << e;
    EXPECT_NE(e.find(b.message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "message is one line: " << e;
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, CsgParserBadInput,
    ::testing::Values(
        BadInput{"Empty", "", "t.csg:1:1", "empty"},
        BadInput{"MatrixWithABoolean", "multmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, true]]) { cube(size = 1); }",
                 "t.csg:1:12", "4x4 matrix"},
        BadInput{"PointWithAString", "polyhedron(points = [[0, 0, 0], [1, 0, \"x\"], [0, 1, 0]], faces = [[0, 1, 2]]);",
                 "t.csg:1:21", "3-vectors of numbers"},
        BadInput{"RowWithoutComma", "polyhedron(points = [[0, 0 0]], faces = [[0, 1, 2]]);", "t.csg:1:28", "expected ']'"},
        BadInput{"SignBeforeVector", "cube(size = -[1, 2, 3]);", "t.csg:1:13", "unary sign"},
        BadInput{"MissingSemicolon", "union() {\n\tcube(size = 1)\n}", "t.csg:3:1", "expected ';'"},
        BadInput{"MissingSemicolonAtEnd", "cube(size = 1)\n", "t.csg:2:1", "expected ';'"},
        BadInput{"MissingBrace", "union() {\n\tcube(size = 1);\n", "t.csg:3:1", "missing '}'"},
        BadInput{"StrayBrace", "cube(size = 1);\n}", "t.csg:2:1", "unexpected '}'"},
        BadInput{"UnclosedArgs", "cube(size = 1;", "t.csg:1:14", "expected ')'"},
        BadInput{"UnknownModule", "union() {\n\tcyl(r = 1);\n}", "t.csg:2:2", "unknown module 'cyl'"},
        BadInput{"BadCharacter", "cube(size = @);", "t.csg:1:13", "unexpected character '@'"},
        BadInput{"MalformedNumber", "cube(size = 1.2.3);", "t.csg:1:13", "malformed number"},
        BadInput{"ExponentWithoutDigits", "cube(size = 1e);", "t.csg:1:13", "exponent"},
        BadInput{"UnterminatedString", "import(file = \"a.stl);", "t.csg:1:15", "unterminated string"},
        BadInput{"WrongTypeString", "sphere(r = \"big\");", "t.csg:1:12", "r must be a number, not a string"},
        BadInput{"WrongTypeVector", "sphere(r = [1, 2]);", "t.csg:1:12", "r must be a number, not a vector"},
        BadInput{"WrongTypeCenter", "cube(size = 1, center = \"yes\");", "t.csg:1:25", "center must be true or false"},
        BadInput{"CubeSizeTwoNumbers", "cube(size = [1, 2]);", "t.csg:1:13", "vector of 3 numbers"},
        BadInput{"NanRadius", "sphere(r = nan);", "t.csg:1:12", "must be finite, not nan"},
        BadInput{"InfHeight", "cylinder(h = inf, r = 1);", "t.csg:1:14", "must be finite, not inf"},
        BadInput{"NegativeInfHeight", "cylinder(h = -inf, r = 1);", "t.csg:1:14", "must be finite"},
        BadInput{"HugeNumber", "cube(size = 1e999);", "t.csg:1:13", "out of range"},
        BadInput{"NanInMatrix", "multmatrix([[nan, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = 1); }",
                 "t.csg:1:12", "not finite"},
        BadInput{"MatrixWrongShape", "multmatrix([[1, 0, 0], [0, 1, 0], [0, 0, 1]]) { cube(size = 1); }", "t.csg:1:12",
                 "does not have 4 numbers"},
        BadInput{"NegativeCube", "cube(size = [1, -2, 3]);", "t.csg:1:13", "must not be negative"},
        BadInput{"NegativeRadius", "sphere(r = -1);", "t.csg:1:12", "must not be negative"},
        BadInput{"NegativeHeight", "union() {\n  cylinder(h = -3, r = 1);\n}", "t.csg:2:16", "h must not be negative"},
        BadInput{"NegativeR2", "cylinder(h = 1, r1 = 1, r2 = -1);", "t.csg:1:30", "r2 must not be negative"},
        BadInput{"PolyhedronBadIndex", "polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 7]]);",
                 "t.csg:1:64", "invalid point index"},
        BadInput{"PolyhedronShortFace", "polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1]]);",
                 "t.csg:1:64", "fewer than 3"},
        BadInput{"PolyhedronTwoCoordinates", "polyhedron(points = [[0, 0], [1, 0], [0, 1]], faces = [[0, 1, 2]]);",
                 "t.csg:1:21", "3 coordinates"},
        BadInput{"PolyhedronNoFaces", "polyhedron(points = [[0, 0, 0]]);", "t.csg:1:1", "no faces"},
        BadInput{"MissingImport", "import(file = \"does-not-exist.stl\");", "t.csg:1:15", "import file not found"},
        BadInput{"ImportWithoutFile", "import(convexity = 1);", "t.csg:1:1", "file name"},
        BadInput{"UnterminatedComment", "cube(size = 1); /* never closed", "t.csg:1:17", "unterminated comment"},
        BadInput{"UnexpectedEnd", "difference() {\n\tcube(size = [1, ", "t.csg:2:18", "end of file"},
        BadInput{"DeepVectors", "cube(size = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["
                                "1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]);",
                 "t.csg:1:77", "nested too deeply"}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return std::string(info.param.name); });

TEST(CsgParser, MissingFileNamesTheFile) {
    try {
        parseCsgFile("/nonexistent/dir/scene.csg");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/scene.csg: ", 0), 0u) << e.what();
    }
}

TEST(CsgParser, BlankFileIsAnEmptySceneWithAWarning) {
    // What OpenSCAD 2021.01 exports for a model with no geometry (Functions/echo.scad).
    Tree t = parse("\n");
    EXPECT_TRUE(t.leaves.empty());
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_NE(t.warnings[0].message.find("no statements"), std::string::npos);
}

TEST(CsgParser, LongRunsOfSignsNeedNoRecursion) {
    std::string text = "sphere(r = " + std::string(200001, '-') + "-1);";  // an even count of 200002 signs
    Tree t = parse(text);
    EXPECT_EQ(std::get<Sphere>(t.leaves.at(0).primitive).r, 1.0);
    EXPECT_NE(errorOf("sphere(r = " + std::string(100001, '-') + "1);").find("must not be negative"), std::string::npos);
}

namespace {

using strata::test::nested;

std::string errorWith(const std::string& text, const ParseOptions& options) {
    try {
        std::istringstream in(text);
        parseCsg(in, "t.csg", "", options);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(CsgParser, NestingLimitIsTheDocumentedOne) {
    EXPECT_EQ(ParseOptions{}.maxNesting, 1000000);
    EXPECT_EQ(ParseOptions{}.maxNestedShapes, 1000);
}

TEST(CsgParser, NestingExactlyAtTheLimitIsAccepted) {
    // The top level is not a block: a limit of 5 takes 5 blocks inside one
    // another, and refuses the sixth where it opens.
    ParseOptions options;
    options.maxNesting = 5;
    EXPECT_EQ(errorWith(nested(5, "union() {", "cube(size = 1);", "}"), options), "");
    EXPECT_EQ(errorWith(nested(6, "union() {", "cube(size = 1);", "}"), options),
              "t.csg:6:1: nesting too deep (more than 5 blocks)");
    // A statement's block without braces counts as one too.
    EXPECT_EQ(errorWith(nested(5, "color([1, 0, 0, 1])", "cube(size = 1);", ""), options), "");
    EXPECT_EQ(errorWith(nested(6, "color([1, 0, 0, 1])", "cube(size = 1);", ""), options),
              "t.csg:6:1: nesting too deep (more than 5 blocks)");
}

TEST(CsgParser, NestedShapesHaveTheirOwnBudget) {
    // Each of these reads its children into a shape of its own, which
    // building the model walks on the C++ stack: N inside one another are
    // taken, N + 1 refused where the last one opens.
    ParseOptions options;
    options.maxNestedShapes = 4;
    const std::string message = ": nesting too deep (more than 4 hull, minkowski, resize, projection or extrusion levels)";
    struct Case {
        const char* open;
        const char* close;
        int perLine;  // counted nodes a line
    };
    for (const Case& c : {Case{"projection(cut = false) {", "}", 1}, Case{"hull() { difference() {", "} }", 1},
                          Case{"resize(newsize = [1, 1, 1]) { difference() {", "} }", 1},
                          Case{"minkowski() {", "}", 1}, Case{"rotate_extrude() { projection() {", "} }", 2},
                          Case{"linear_extrude(height = 1) { projection(cut = false) {", "} }", 2}}) {
        const int lines = 4 / c.perLine;
        EXPECT_EQ(errorWith(nested(lines, c.open, "cube(size = 1);", c.close), options), "") << c.open;
        EXPECT_EQ(errorWith(nested(lines + 1, c.open, "cube(size = 1);", c.close), options),
                  "t.csg:" + std::to_string(lines + 1) + ":1" + message)
            << c.open;
    }
    // Blocks that make no shape do not count, nor do 2D operations inside an extrusion.
    EXPECT_EQ(errorWith(nested(50, "difference() {", "cube(size = 1);", "}"), options), "");
    EXPECT_EQ(errorWith("linear_extrude(height = 1) {\n" + nested(50, "hull() {", "square(size = 1);", "}") + "}", options),
              "");
    // Nor do dropped ones.
    EXPECT_EQ(errorWith(nested(50, "*hull() {", "cube(size = 1);", "}"), options), "");
}

TEST(CsgParser, DeeplyNestedShapesAreRefusedByDefault) {
    // Far past the budget, where building the model used to run out of stack.
    const std::string e = errorOf(nested(5000, "projection(cut = false) {", "cube(size = 1);", "}"));
    EXPECT_EQ(e, "t.csg:1001:1: nesting too deep (more than 1000 hull, minkowski, resize, projection or extrusion levels)");
}

TEST(CsgParser, LongTransformChainsEndWithoutRecursion) {
    // What a million nested multmatrix() leave each leaf: a chain a million
    // steps long, let go of without a C++ frame a step.
    auto chain = std::make_shared<const TransformStep>(TransformStep{glm::dmat4(1.0), nullptr});
    for (int i = 0; i < 1000000; ++i) chain = std::make_shared<const TransformStep>(TransformStep{glm::dmat4(1.0), chain});
    auto shared = chain->previous;  // a part still held elsewhere stays whole
    chain.reset();
    int length = 0;
    for (const TransformStep* s = shared.get(); s != nullptr; s = s->previous.get()) ++length;
    EXPECT_EQ(length, 1000000);
    shared.reset();
}

TEST(CsgParser, DeepNestingNeedsNoDeepRecursion) {
    // 20000 nested groups: the parser keeps its own stack, not the C++ one.
    std::string text;
    const int depth = 20000;
    for (int i = 0; i < depth; ++i) text += "union() {\n";
    text += "cube(size = 1);\n";
    for (int i = 0; i < depth; ++i) text += "}\n";
    Tree t = parse(text);
    EXPECT_EQ(t.leaves.size(), 1u);
    std::string braceless;
    for (int i = 0; i < depth; ++i) braceless += "multmatrix([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) ";
    braceless += "cube(size = 1);";
    Tree t2 = parse(braceless);
    ASSERT_EQ(t2.leaves.size(), 1u);
    EXPECT_EQ(t2.leaves[0].transform[3][0], static_cast<double>(depth));
}
