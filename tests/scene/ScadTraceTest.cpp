// ScadTrace: a CSG export's nodes traced back to the calls in the .scad that
// made them, where only one can have. The exports below are what OpenSCAD
// 2021.01 writes for the sources beside them (`openscad -o x.csg`).

#include <gtest/gtest.h>

#include <sstream>

#include "strata/core/Error.h"
#include "strata/scene/CsgParser.h"
#include "strata/scene/ScadTrace.h"

using namespace strata;
using namespace strata::scene;

namespace {

std::string at(const std::optional<SourceLocation>& where) { return where ? where->str() : "untraced"; }

}  // namespace

TEST(ScadTrace, AOneCallNodeIsWhereItsCallIs) {
    const ScadTrace trace("cube(size = [5, 5, 5], center = false);\n"
                          "multmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
                          "\tsphere($fn = 0, $fa = 12, $fs = 2, r = 1);\n"
                          "}\n",
                          {{"a.scad", "// a cube( in a comment, and /* sphere( */ in another\n"
                                      "cube(5);\n"
                                      "translate([10, 0, 0])\n"
                                      "    sphere\n"
                                      "      (1);  echo(\"cube(\");\n"}});
    EXPECT_EQ(at(trace.locate(1)), "a.scad:2:1");
    EXPECT_EQ(at(trace.locate(3)), "a.scad:4:5");  // the name, though its '(' is a line further
    EXPECT_EQ(at(trace.locate(2)), "untraced");    // translate is written multmatrix
    EXPECT_EQ(at(trace.locate(4)), "untraced");
    EXPECT_EQ(at(trace.locate(0)), "untraced");
    EXPECT_EQ(at(trace.locate(5)), "untraced");
    EXPECT_EQ(trace.tracedLines(), 2);
}

TEST(ScadTrace, ANameCalledTwiceIsNotTraced) {
    // Two cube() calls: either can have made either node. A loop or a module
    // called twice makes several nodes of one call: all trace to it.
    const ScadTrace trace("cube(size = [1, 1, 1], center = false);\n"
                          "cube(size = [2, 2, 2], center = false);\n"
                          "group() {\n"
                          "\tsphere($fn = 0, $fa = 12, $fs = 2, r = 1);\n"
                          "}\n"
                          "group() {\n"
                          "\tsphere($fn = 0, $fa = 12, $fs = 2, r = 1);\n"
                          "}\n",
                          {{"a.scad", "cube(1);\ncube(2);\nmodule ball() sphere(1);\nball();\nball();\n"}});
    EXPECT_EQ(at(trace.locate(1)), "untraced");
    EXPECT_EQ(at(trace.locate(2)), "untraced");
    EXPECT_EQ(at(trace.locate(4)), "a.scad:3:15");
    EXPECT_EQ(at(trace.locate(7)), "a.scad:3:15");
    EXPECT_EQ(at(trace.locate(3)), "untraced");  // a module's group: the name `ball` is not written in the export
}

TEST(ScadTrace, ImportsAndTextsAreTracedByTheirStrings) {
    const ScadTrace trace(
        "import(file = \"b.stl\", layer = \"\", origin = [0, 0], scale = 1, convexity = 1, $fn = 0, $fa = 12, $fs = 2, "
        "timestamp = 1);\n"
        "import(file = \"c.stl\", layer = \"\", origin = [0, 0], scale = 1, convexity = 1, $fn = 0, $fa = 12, $fs = 2, "
        "timestamp = 1);\n"
        "text(text = \"Hi \\\"you\\\"\", size = 10, spacing = 1, font = \"\", direction = \"ltr\", language = \"en\", "
        "script = \"Latn\", halign = \"left\", valign = \"baseline\", $fn = 0, $fa = 12, $fs = 2);\n"
        "surface(file = \"h.dat\", center = false, invert = false, timestamp = 1);\n",
        {{"a.scad", "name = \"c.stl\";\nimport(\"b.stl\");\nimport(name);\nuse <lib.scad>\nlabel();\n"},
         {"lib.scad", "module label() {\n  text(\"Hi \\\"you\\\"\");\n  text(str(\"Bye\"));\n  surface(file = \"h.dat\");\n}\n"}});
    EXPECT_EQ(at(trace.locate(1)), "a.scad:2:1");  // the only import() holding "b.stl"
    EXPECT_EQ(at(trace.locate(2)), "untraced");    // from a variable, and not the only import()
    EXPECT_EQ(at(trace.locate(3)), "lib.scad:2:3");
    EXPECT_EQ(at(trace.locate(4)), "lib.scad:4:3");
}

TEST(ScadTrace, TheParserPositionsNodesAndMessagesThroughIt) {
    const std::string csg = "cube(size = [1, 1, 1], center = false);\n"
                            "multmatrix([[1, 0, 0, 3], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
                            "\tsphere($fn = 5000, $fa = 12, $fs = 2, r = 1);\n"
                            "}\n";
    const auto trace = std::make_shared<const ScadTrace>(csg, std::vector<ScadTrace::Source>{
                                                                  {"m.scad", "cube(1);\ntranslate([3, 0, 0]) sphere(1, $fn = 5000);\nif (false) cube(2);\n"}});
    ParseOptions options;
    options.locate = [trace](int line) { return trace->locate(line); };
    std::istringstream in(csg);
    const Tree tree = parseCsg(in, "m.scad (CSG export)", ".", options);
    ASSERT_EQ(tree.leaves.size(), 2u);
    // Two cube() calls: the cube keeps its place in the export.
    EXPECT_EQ(tree.leaves[0].where.str(), "m.scad (CSG export):1:1");
    EXPECT_EQ(tree.leaves[1].where.str(), "m.scad:2:22");
    ASSERT_EQ(tree.warnings.size(), 1u);
    EXPECT_EQ(tree.warnings[0].message.rfind("m.scad:2:22: warning: $fn", 0), 0u) << tree.warnings[0].message;
}
