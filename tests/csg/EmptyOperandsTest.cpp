// Hulls, Minkowski sums and resizes that make no solid, as operands of the
// CSG tree, against OpenSCAD 2021.01's results. Each scene is OpenSCAD's CSG
// export (`openscad -o x.csg x.scad`) of the .scad above it; the expected
// result is what `openscad -o x.off x.scad` makes of the same model:
// "Current top level object is empty." where the tree must compile to the
// empty set, else the box and volume of its mesh.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "strata/csg/CompiledTree.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;

namespace {

struct Compiled {
    scene::Tree tree;
    model::Model model;
    csg::CompiledTree code;
};

// The scene as strata-render takes it: parsed, meshed, and compiled with the
// leaves that have no triangles as the empty set.
Compiled compile(const std::string& text) {
    Compiled c;
    std::istringstream in(text);
    c.tree = scene::parseCsg(in, "t.csg", "");
    c.model = model::buildModel(c.tree);
    std::vector<bool> empty(c.model.leafMeshes.size());
    for (std::size_t i = 0; i < empty.size(); ++i) empty[i] = c.model.leafMeshes[i].triangles.empty();
    c.code = csg::compileTree(c.tree, empty);
    return c;
}

double volume(const mesh::Mesh& m) {
    double v6 = 0.0;
    for (const auto& t : m.triangles) v6 += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]]));
    return v6 / 6.0;
}

const char* const kCube10 = "\tcube(size = [10, 10, 10], center = false);\n";

}  // namespace

TEST(EmptyOperands, AHullMinkowskiOrResizeOfNothingIsEmptyUnderAnIntersection) {
    const std::vector<std::pair<const char*, std::string>> scenes = {
        {"intersection() { cube(10); minkowski() { } }",
         std::string("intersection() {\n") + kCube10 + "\tminkowski(convexity = 0);\n}\n"},
        {"intersection() { cube(10); hull() { } }", std::string("intersection() {\n") + kCube10 + "\thull();\n}\n"},
        {"intersection() { cube(10); resize([5, 5, 5]) { } }",
         std::string("intersection() {\n") + kCube10 + "\tresize(newsize = [5,5,5], auto = [0,0,0], convexity = 0);\n}\n"},
        {"intersection() { cube(10); minkowski() { group(); } }",
         std::string("intersection() {\n") + kCube10 + "\tminkowski(convexity = 0) {\n\t\tgroup();\n\t}\n}\n"},
        {"intersection() { cube(10); minkowski() { cube(0); } }",
         std::string("intersection() {\n") + kCube10 +
             "\tminkowski(convexity = 0) {\n\t\tcube(size = [0, 0, 0], center = false);\n\t}\n}\n"},
        {"intersection() { cube(10); hull() { cube(0); } }",
         std::string("intersection() {\n") + kCube10 + "\thull() {\n\t\tcube(size = [0, 0, 0], center = false);\n\t}\n}\n"},
        // The square is ignored (2D in a 3D operation), the cube is empty.
        {"intersection() { cube(10); minkowski() { cube(0); square(3); } }",
         std::string("intersection() {\n") + kCube10 +
             "\tminkowski(convexity = 0) {\n\t\tcube(size = [0, 0, 0], center = false);\n"
             "\t\tsquare(size = [3, 3], center = false);\n\t}\n}\n"},
        // Empty only once its operand is evaluated: two cubes that do not meet.
        {"intersection() { cube(10); minkowski() { intersection() { cube(1); translate([5, 0, 0]) cube(1); } } }",
         std::string("intersection() {\n") + kCube10 +
             "\tminkowski(convexity = 0) {\n\t\tintersection() {\n\t\t\tcube(size = [1, 1, 1], center = false);\n"
             "\t\t\tmultmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
             "\t\t\t\tcube(size = [1, 1, 1], center = false);\n\t\t\t}\n\t\t}\n\t}\n}\n"},
        {"difference() { minkowski(); cube(3); }",
         "difference() {\n\tminkowski(convexity = 0);\n\tcube(size = [3, 3, 3], center = false);\n}\n"},
    };
    for (const auto& [scad, csg] : scenes) {
        const Compiled c = compile(csg);
        EXPECT_EQ(c.code.kind, csg::CompiledTree::Kind::Empty) << scad;
    }
}

// difference() { cube(10); minkowski() { } }: OpenSCAD's result is the
// whole cube, [0, 10]^3.
TEST(EmptyOperands, AnEmptySubtrahendTakesNothingAway) {
    const Compiled c = compile(std::string("difference() {\n") + kCube10 + "\tminkowski(convexity = 0);\n}\n");
    ASSERT_EQ(c.code.kind, csg::CompiledTree::Kind::Code);
    ASSERT_EQ(c.code.operandLeaf.size(), 1u);
    EXPECT_EQ(c.model.bounds.min, glm::dvec3(0.0));
    EXPECT_EQ(c.model.bounds.max, glm::dvec3(10.0));
    EXPECT_EQ(csg::disassemble(c.code), csg::disassemble(compile(kCube10).code));  // the cube alone
}

// OpenSCAD leaves an empty operand out of a Minkowski sum (the sum is that
// of the other operands), whether it is empty by its parameters or by its
// evaluation.
TEST(EmptyOperands, AnEmptyOperandIsLeftOutOfAMinkowskiSum) {
    struct Case {
        const char* scad;
        std::string csg;
        glm::dvec3 min, max;
        double volume;
    };
    const std::string box2 = "\t\tcube(size = [2, 2, 2], center = false);\n";
    const std::string disjoint = "\t\tintersection() {\n\t\t\tcube(size = [1, 1, 1], center = false);\n"
                                 "\t\t\tmultmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
                                 "\t\t\t\tcube(size = [1, 1, 1], center = false);\n\t\t\t}\n\t\t}\n";
    const std::vector<Case> cases = {
        {"minkowski() { cube(0); cube(5); }",
         "minkowski(convexity = 0) {\n\tcube(size = [0, 0, 0], center = false);\n\tcube(size = [5, 5, 5], center = false);\n}\n",
         glm::dvec3(0), glm::dvec3(5), 125.0},
        {"minkowski() { cube(5); sphere(0); }",
         "minkowski(convexity = 0) {\n\tcube(size = [5, 5, 5], center = false);\n\tsphere($fn = 0, $fa = 12, $fs = 2, r = 0);\n}\n",
         glm::dvec3(0), glm::dvec3(5), 125.0},
        {"minkowski() { cube([5, 5, 0]); cube(1); }",
         "minkowski(convexity = 0) {\n\tcube(size = [5, 5, 0], center = false);\n\tcube(size = [1, 1, 1], center = false);\n}\n",
         glm::dvec3(0), glm::dvec3(1), 1.0},
        {"minkowski() { cube(2); cylinder(h = 0, r = 1); }",
         "minkowski(convexity = 0) {\n" + box2.substr(1) +
             "\tcylinder($fn = 0, $fa = 12, $fs = 2, h = 0, r1 = 1, r2 = 1, center = false);\n}\n",
         glm::dvec3(0), glm::dvec3(2), 8.0},
        {"minkowski() { intersection() { cube(1); translate([5, 0, 0]) cube(1); } cube(2); }",
         "minkowski(convexity = 0) {\n" + disjoint + box2 + "}\n", glm::dvec3(0), glm::dvec3(2), 8.0},
        {"minkowski() { cube(2); intersection() { cube(1); translate([5, 0, 0]) cube(1); } }",
         "minkowski(convexity = 0) {\n" + box2 + disjoint + "}\n", glm::dvec3(0), glm::dvec3(2), 8.0},
        // A part of a union that is empty adds nothing to its operand.
        {"minkowski() { union() { cube(0); translate([10, 0, 0]) cube(3); } cube(1); }",
         "minkowski(convexity = 0) {\n\tunion() {\n\t\tcube(size = [0, 0, 0], center = false);\n"
         "\t\tmultmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
         "\t\t\tcube(size = [3, 3, 3], center = false);\n\t\t}\n\t}\n\tcube(size = [1, 1, 1], center = false);\n}\n",
         glm::dvec3(10, 0, 0), glm::dvec3(14, 4, 4), 64.0},
    };
    for (const Case& k : cases) {
        const Compiled c = compile(k.csg);
        ASSERT_EQ(c.code.kind, csg::CompiledTree::Kind::Code) << k.scad;
        ASSERT_EQ(c.code.operandLeaf.size(), 1u) << k.scad;
        EXPECT_EQ(c.model.bounds.min, k.min) << k.scad;
        EXPECT_EQ(c.model.bounds.max, k.max) << k.scad;
        const auto leaf = static_cast<std::size_t>(c.code.operandLeaf[0]);
        EXPECT_NEAR(volume(c.model.leafMeshes[leaf]), k.volume, 1e-9) << k.scad;
    }
}
