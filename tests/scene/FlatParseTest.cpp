// How the reader turns 2D statements and extrusions into leaves: the flat
// tree each leaf carries, the extrusions' arguments as OpenSCAD 2021.01 reads
// them, flat results outside extrusions, and what is ignored with a warning.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <variant>

#include <glm/geometric.hpp>

#include "../mesh/MeshTestUtil.h"
#include "strata/exact/Exact.h"
#include "strata/mesh/Mesh.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using namespace strata::scene;

namespace {

Tree parse(const std::string& text) {
    std::istringstream in(text);
    return parseCsg(in, "t.csg", "");
}

std::string errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

const FlatNode& node(const FlatTree& t, int i) { return t.nodes.at(static_cast<std::size_t>(i)); }

// Signed volume by the divergence theorem, computed here from the triangles.
double volume(const mesh::Mesh& m) {
    double v6 = 0.0;
    for (const auto& t : m.triangles) v6 += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]]));
    return v6 / 6.0;
}

}  // namespace

TEST(FlatParse, LinearExtrudeIsOneLeafHoldingItsShape) {
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tlinear_extrude(height = 5, center = true, convexity = 1, twist = 90, slices = 8, scale = [1, 0.5], "
        "$fn = 0, $fa = 12, $fs = 2) {\n"
        "\t\tdifference() {\n"
        "\t\t\tsquare(size = [10, 10], center = true);\n"
        "\t\t\tmultmatrix([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) circle($fn = 0, $fa = 12, $fs = 2, r = 3);\n"
        "\t\t}\n\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.warnings.empty());
    const Leaf& leaf = t.leaves[0];
    EXPECT_EQ(leaf.transform[3][0], 5.0);  // the extrusion's own placement stays on the leaf
    EXPECT_EQ(leaf.where.line, 2);
    const auto& e = std::get<LinearExtrude>(leaf.primitive);
    EXPECT_EQ(e.height, 5.0);
    EXPECT_TRUE(e.center);
    EXPECT_TRUE(e.hasTwist);
    EXPECT_EQ(e.twist, 90.0);
    EXPECT_TRUE(e.hasSlices);
    EXPECT_EQ(e.slices, 8);
    EXPECT_EQ(e.scale, glm::dvec2(1.0, 0.5));

    // union (the extrusion's children) > difference > square, transform > circle
    const FlatTree& s = e.shape;
    const FlatNode& root = node(s, s.root);
    EXPECT_EQ(root.op, FlatOp::Union);
    ASSERT_EQ(root.children.size(), 1u);
    const FlatNode& diff = node(s, root.children[0]);
    EXPECT_EQ(diff.op, FlatOp::Difference);
    ASSERT_EQ(diff.children.size(), 2u);
    const FlatNode& sq = node(s, diff.children[0]);
    EXPECT_EQ(sq.op, FlatOp::Shape);
    EXPECT_EQ(std::get<Square>(s.shapes.at(static_cast<std::size_t>(sq.shape))).size, glm::dvec2(10, 10));
    const FlatNode& moved = node(s, diff.children[1]);
    EXPECT_EQ(moved.op, FlatOp::Transform);
    EXPECT_EQ(moved.matrix[3][0], 1.0);  // local to the extrusion, not composed with the outer translate
    ASSERT_EQ(moved.children.size(), 1u);
    EXPECT_EQ(std::get<Circle>(s.shapes.at(static_cast<std::size_t>(node(s, moved.children[0]).shape))).r, 3.0);
    // Children come after their parents.
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
        for (int c : s.nodes[i].children) EXPECT_GT(static_cast<std::size_t>(c), i);
}

TEST(FlatParse, ExtrusionArgumentsAsOpenScadReadsThem) {
    // No twist written, or a zero twist: no twist rule; slices 0: no slices rule;
    // negative height: nothing; a negative scale: 0; a scalar scale: both axes.
    const Tree t = parse(
        "linear_extrude(height = -2, twist = 0, slices = 0, scale = -1) square(size = 1);\n"
        "linear_extrude(height = 3, scale = 2) square(size = 1);\n"
        "rotate_extrude(angle = 720, convexity = 2, $fn = 7) square(size = 1);\n"
        "rotate_extrude(angle = 90, start = 30) square(size = 1);\n");
    ASSERT_EQ(t.leaves.size(), 4u);
    const auto& a = std::get<LinearExtrude>(t.leaves[0].primitive);
    EXPECT_EQ(a.height, 0.0);
    EXPECT_FALSE(a.hasTwist);
    EXPECT_FALSE(a.hasSlices);
    EXPECT_EQ(a.scale, glm::dvec2(0.0, 0.0));
    EXPECT_EQ(std::get<LinearExtrude>(t.leaves[1].primitive).scale, glm::dvec2(2.0, 2.0));
    const auto& r = std::get<RotateExtrude>(t.leaves[2].primitive);
    EXPECT_EQ(r.angle, 360.0);  // out of (-360, 360]
    EXPECT_FALSE(r.hasStart);
    EXPECT_EQ(r.fragments.fn, 7.0);
    const auto& r2 = std::get<RotateExtrude>(t.leaves[3].primitive);
    EXPECT_TRUE(r2.hasStart);
    EXPECT_EQ(r2.start, 30.0);
}

TEST(FlatParse, FlatObjectsOutsideExtrusionsAreOneSlab) {
    // A 2D boolean at the top level, and a sibling flat object: one flat
    // result, as OpenSCAD unions them, with each part under its own placement.
    const Tree t = parse(
        "difference() {\n\tsquare(size = [10, 10], center = false);\n"
        "\tmultmatrix([[1, 0, 0, 3], [0, 1, 0, 3], [0, 0, 1, 0], [0, 0, 0, 1]]) circle(r = 2);\n}\n"
        "polygon(points = [[20, 0], [25, 0], [20, 5]], paths = undef, convexity = 1);\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.isFlat());
    const FlatTree& s = std::get<FlatSlab>(t.leaves[0].primitive).shape;
    const FlatNode& root = node(s, s.root);
    EXPECT_EQ(root.op, FlatOp::Union);
    ASSERT_EQ(root.children.size(), 2u);
    const FlatNode& placed = node(s, root.children[0]);
    EXPECT_EQ(placed.op, FlatOp::Transform);
    EXPECT_EQ(node(s, placed.children.at(0)).op, FlatOp::Difference);
}

TEST(FlatParse, AnOperationTakesItsFirstChildsDimension) {
    // OpenSCAD's exact evaluation: an operation, the top level included, is
    // 2D or 3D by its first child, and a child of the other dimension is
    // empty, with a warning naming it.
    const Tree flatFirst = parse("square(size = 4);\ncube(size = 2);\n");
    ASSERT_EQ(flatFirst.leaves.size(), 1u);
    EXPECT_TRUE(flatFirst.isFlat());
    ASSERT_EQ(flatFirst.warnings.size(), 1u);
    EXPECT_EQ(flatFirst.warnings[0].message.rfind("t.csg:2:1: warning: a solid in a union of 2D objects is ignored", 0), 0u)
        << flatFirst.warnings[0].message;

    const Tree solidFirst = parse("cube(size = 2);\nsquare(size = 4);\n");
    ASSERT_EQ(solidFirst.leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Cube>(solidFirst.leaves[0].primitive));
    ASSERT_EQ(solidFirst.warnings.size(), 1u);
    EXPECT_EQ(solidFirst.warnings[0].message.rfind("t.csg:2:1: warning: a 2D object in a union of solids is ignored", 0),
              0u)
        << solidFirst.warnings[0].message;

    // A difference loses a flat subtrahend; an intersection with one is empty.
    const Tree cut = parse("difference() {\n\tcube(size = 10);\n\tcircle(r = 3);\n\tsphere(r = 2);\n}\n");
    ASSERT_EQ(cut.leaves.size(), 2u);
    EXPECT_TRUE(std::holds_alternative<Cube>(cut.leaves[0].primitive));
    EXPECT_TRUE(std::holds_alternative<Sphere>(cut.leaves[1].primitive));
    EXPECT_EQ(cut.nodes[static_cast<std::size_t>(cut.root)].kind, NodeKind::Difference);
    ASSERT_EQ(cut.warnings.size(), 1u);
    EXPECT_EQ(cut.warnings[0].message.rfind("t.csg:3:2: warning: a 2D object in a difference of solids", 0), 0u)
        << cut.warnings[0].message;
    const Tree meet = parse("intersection() {\n\tcube(size = 10);\n\tcircle(r = 3);\n}\n");
    EXPECT_TRUE(meet.leaves.empty());
    EXPECT_EQ(meet.warnings.size(), 1u);

    // A 2D difference loses a solid subtrahend and stays flat.
    const Tree flatCut = parse("difference() {\n\tsquare(size = 10);\n\tcube(size = 3);\n\tcircle(r = 2);\n}\n");
    ASSERT_EQ(flatCut.leaves.size(), 1u);
    EXPECT_TRUE(flatCut.isFlat());
    const FlatTree& shape = std::get<FlatSlab>(flatCut.leaves[0].primitive).shape;
    EXPECT_EQ(node(shape, shape.root).op, FlatOp::Difference);
    EXPECT_EQ(node(shape, shape.root).children.size(), 2u);

    // Nothing has no dimension: an empty group first changes nothing.
    const Tree afterNothing = parse("group();\ncube(size = 2);\nsquare(size = 4);\n");
    ASSERT_EQ(afterNothing.leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Cube>(afterNothing.leaves[0].primitive));

    // A flat object lifted out of its plane is drawn where it is, not merged.
    const Tree lifted = parse("union() {\n\tsquare(size = 4);\n"
                              "\tmultmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]) square(size = 4);\n}\n");
    EXPECT_EQ(lifted.leaves.size(), 2u);
}

TEST(FlatParse, SolidsInsideFlatOperationsAreIgnoredWithAWarning) {
    const Tree t = parse(
        "linear_extrude(height = 1) {\n\tsquare(size = 1);\n\tcube(size = 3);\n"
        "\troof() { circle(r = 1); }\n\t%circle(r = 5);\n\t*circle(r = 6);\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const FlatTree& s = std::get<LinearExtrude>(t.leaves[0].primitive).shape;
    const FlatNode& root = node(s, s.root);
    // square, the ignored cube and the roof strata cannot make yet (empty children, which OpenSCAD keeps);
    // the background and disabled circles are not children at all.
    ASSERT_EQ(root.children.size(), 3u);
    EXPECT_EQ(node(s, root.children[1]).op, FlatOp::Empty);
    EXPECT_EQ(node(s, root.children[2]).op, FlatOp::Empty);
    ASSERT_EQ(t.warnings.size(), 2u);
    EXPECT_NE(t.warnings[0].message.find("t.csg:3:2: warning: 'cube' is a 3D object inside a 2D operation"),
              std::string::npos)
        << t.warnings[0].message;
    EXPECT_EQ(t.unsupported.at("roof"), 1);
}

TEST(FlatParse, ShapesAndTheirArguments) {
    const Tree t = parse(
        "linear_extrude(height = 1) {\n"
        "\tpolygon(points = [[0, 0], [4, 0], [4, 4], [0, 4], [1, 1], [2, 1], [2, 2]], paths = [[0, 1, 2, 3], [4, 5, 9]], "
        "convexity = 1);\n"
        "\ttext(text = \"Hi\", size = 7, spacing = 1.2, font = \"Liberation Serif\", direction = \"ltr\", language = "
        "\"en\", script = \"Latn\", halign = \"center\", valign = \"default\", $fn = 0, $fa = 12, $fs = 2);\n"
        "\toffset(delta = 2, chamfer = true, $fn = 0, $fa = 12, $fs = 2) square(size = [1, 2]);\n"
        "\toffset(r = -1, $fn = 8) circle(d = 10);\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const FlatTree& s = std::get<LinearExtrude>(t.leaves[0].primitive).shape;
    ASSERT_EQ(s.shapes.size(), 4u);
    const auto& p = std::get<Polygon>(s.shapes[0]);
    EXPECT_EQ(p.points.size(), 7u);
    ASSERT_EQ(p.paths.size(), 2u);
    EXPECT_EQ(p.paths[1].size(), 2u);  // index 9 is past the points: skipped, with a warning
    ASSERT_EQ(t.warnings.size(), 1u);
    const auto& text = std::get<Text>(s.shapes[1]);
    EXPECT_EQ(text.text, "Hi");
    EXPECT_EQ(text.size, 7.0);
    EXPECT_EQ(text.spacing, 1.2);
    EXPECT_EQ(text.font, "Liberation Serif");
    EXPECT_EQ(text.halign, "center");
    EXPECT_EQ(text.valign, "baseline");
    const FlatNode& root = node(s, s.root);
    const FlatNode& chamfer = node(s, root.children.at(2));
    EXPECT_EQ(chamfer.op, FlatOp::Offset);
    EXPECT_EQ(chamfer.offset.join, Offset::Join::Square);
    EXPECT_EQ(chamfer.offset.amount, 2.0);
    const FlatNode& round = node(s, root.children.at(3));
    EXPECT_EQ(round.offset.join, Offset::Join::Round);
    EXPECT_EQ(round.offset.amount, -1.0);
    EXPECT_EQ(std::get<Circle>(s.shapes[3]).r, 5.0);
}

TEST(FlatParse, BadFlatArgumentsNameTheirPosition) {
    EXPECT_EQ(errorOf("linear_extrude(height = 1) polygon(points = [[0, 0, 1]]);"),
              "t.csg:1:45: point 0 does not have 2 coordinates");
    EXPECT_EQ(errorOf("square(size = [1, 2, 3]);"), "t.csg:1:15: size must be a number or a vector of 2 numbers");
    EXPECT_EQ(errorOf("circle(r = -1);"), "t.csg:1:12: r must not be negative");
    EXPECT_EQ(errorOf("linear_extrude(height = 1) text(text = \"a\", size = \"big\");"),
              "t.csg:1:52: size must be a number, not a string");
    EXPECT_EQ(errorOf("linear_extrude(height = 1) squircle();"), "t.csg:1:28: unknown module 'squircle'");
    EXPECT_EQ(errorOf("surface(file = \"missing.dat\");"), "t.csg:1:16: surface file not found: missing.dat");
}

TEST(FlatParse, HullOfSolidsIsOneLeafOfItsPartsPlacedByTheHullsTransform) {
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) color([1, 0, 0, 1]) hull() {\n"
        "\tmultmatrix([[1, 0, 0, 4], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(r = 1);\n"
        "\tgroup() { cube(size = 1); color([0, 1, 0, 1]) cylinder(h = 2, r = 1); }\n"
        "\t%multmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]) cube(size = 9);\n}\n");
    ASSERT_EQ(t.leaves.size(), 2u);  // the hull and the background cube
    ASSERT_EQ(t.background.size(), 1u);
    const Node& root = t.nodes[static_cast<std::size_t>(t.root)];
    ASSERT_EQ(root.kind, NodeKind::Leaf);
    const Leaf& leaf = t.leaves[static_cast<std::size_t>(root.leaf)];
    const auto& h = std::get<Hull>(leaf.primitive);
    ASSERT_EQ(h.parts.size(), 3u);
    EXPECT_TRUE(h.summands.empty());
    EXPECT_EQ(h.parts[0].transform[3][0], 4.0);  // each part placed relative to the hull
    EXPECT_EQ(leaf.transform[3][0], 10.0);       // and the hull by its own transform
    EXPECT_EQ(*leaf.color, glm::dvec4(1, 0, 0, 1));  // the colour outside the hull, not the parts'
    // The '%' cube is drawn on its own, in the world: both translations.
    const Leaf& background = t.leaves[static_cast<std::size_t>(t.nodes[static_cast<std::size_t>(t.background[0])].leaf)];
    EXPECT_EQ(background.display, Display::Background);
    EXPECT_EQ(background.transform[3][0], 10.0);
    EXPECT_EQ(background.transform[3][2], 5.0);
}

TEST(FlatParse, MinkowskiOfUnionsIsAUnionOfHulls) {
    const Tree t = parse(
        "minkowski() {\n\tunion() { cube(size = 1); multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], "
        "[0, 0, 0, 1]]) cube(size = 1); }\n\tsphere(r = 0.5);\n\tcylinder(h = 1, r = 0.2);\n}\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    const Node& root = t.nodes[static_cast<std::size_t>(t.root)];
    EXPECT_EQ(root.kind, NodeKind::Union);
    ASSERT_EQ(root.children.size(), 2u);
    for (const Leaf& leaf : t.leaves) {
        const auto& h = std::get<Hull>(leaf.primitive);
        EXPECT_EQ(h.parts.size(), 1u);
        ASSERT_EQ(h.summands.size(), 2u);
        EXPECT_TRUE(std::holds_alternative<Sphere>(h.summands[0].primitive));
        EXPECT_TRUE(std::holds_alternative<Cylinder>(h.summands[1].primitive));
    }
}

// OpenSCAD 2021.01's CSG export of
//   translate([10, 0, 0]) minkowski() { union() { cube(2); translate([5, 0, 0]) cube(2); } sphere(1, $fn = 8); }
// `openscad -o x.off` of it: x from 9.07612 to 17.9239, y and z from
// -0.923879 to 2.92388, volume 99.0893 (two disjoint hulls).
TEST(FlatParse, APlacedMinkowskiOfAUnionMovesItsHullsOnce) {
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tminkowski(convexity = 0) {\n\t\tunion() {\n\t\t\tcube(size = [2, 2, 2], center = false);\n"
        "\t\t\tmultmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\t\t\t\tcube(size = [2, 2, 2], center = false);\n\t\t\t}\n\t\t}\n"
        "\t\tsphere($fn = 8, $fa = 12, $fs = 2, r = 1);\n\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    const model::Model model = model::buildModel(t);
    EXPECT_NEAR(model.bounds.min.x, 9.07612, 1e-5);
    EXPECT_NEAR(model.bounds.max.x, 17.9239, 1e-4);
    EXPECT_NEAR(model.bounds.min.y, -0.923879, 1e-6);
    EXPECT_NEAR(model.bounds.max.z, 2.92388, 1e-5);
    EXPECT_NEAR(volume(model.leafMeshes[0]) + volume(model.leafMeshes[1]), 99.0893, 1e-3);
}

// OpenSCAD 2021.01's CSG export of
//   translate([20, 0, 0]) minkowski() { cube(2); %translate([0, 0, 5]) cube(1); cylinder(r = 1, h = 1, $fn = 4); }
// The sum is OpenSCAD's x in [19, 23], y in [-1, 3], z in [0, 3], volume 42;
// the '%' cube takes no part in it and is drawn where OpenSCAD's preview
// draws it, at [20, 21] x [0, 1] x [5, 6].
TEST(FlatParse, ABackgroundChildOfAPlacedMinkowskiStaysInTheWorld) {
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 20], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tminkowski(convexity = 0) {\n\t\tcube(size = [2, 2, 2], center = false);\n"
        "%\t\tmultmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]) {\n"
        "\t\t\tcube(size = [1, 1, 1], center = false);\n\t\t}\n"
        "\t\tcylinder($fn = 4, $fa = 12, $fs = 2, h = 1, r1 = 1, r2 = 1, center = false);\n\t}\n}\n");
    ASSERT_EQ(t.background.size(), 1u);
    const model::Model model = model::buildModel(t);
    const Node& root = t.nodes[static_cast<std::size_t>(t.root)];
    ASSERT_EQ(root.kind, NodeKind::Leaf);
    const mesh::Mesh& sum = model.leafMeshes[static_cast<std::size_t>(root.leaf)];
    const mesh::Bounds b = mesh::boundsOf(sum);
    EXPECT_NEAR(b.min.x, 19.0, 1e-12);
    EXPECT_NEAR(b.max.x, 23.0, 1e-12);
    EXPECT_NEAR(b.min.y, -1.0, 1e-12);
    EXPECT_NEAR(b.max.z, 3.0, 1e-12);
    EXPECT_NEAR(volume(sum), 42.0, 1e-9);
    const int backgroundLeaf = t.nodes[static_cast<std::size_t>(t.background[0])].leaf;
    const mesh::Bounds c = mesh::boundsOf(model.leafMeshes[static_cast<std::size_t>(backgroundLeaf)]);
    EXPECT_EQ(c.min, glm::dvec3(20, 0, 5));
    EXPECT_EQ(c.max, glm::dvec3(21, 1, 6));
}

// A 2D minkowski among solids, under a translation: OpenSCAD 2021.01's
// `openscad -o x.svg` of
//   translate([5, 5, 0]) minkowski() { square(3); circle(1, $fn = 4); }
// is the octagon (4,5) (5,4) (8,4) (9,5) (9,8) (8,9) (5,9) (4,8): the square
// grown by the diamond, 9 + 3 * (2 + 2) + 2 = 23 in area, moved once.
TEST(FlatParse, APlacedFlatMinkowskiAmongSolidsMovesOnce) {
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 5], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tminkowski(convexity = 0) {\n\t\tsquare(size = [3, 3], center = false);\n"
        "\t\tcircle($fn = 4, $fa = 12, $fs = 2, r = 1);\n\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.isFlat());
    const model::Model model = model::buildModel(t);
    EXPECT_EQ(model.bounds.min, glm::dvec3(4, 4, -0.5));
    EXPECT_EQ(model.bounds.max, glm::dvec3(9, 9, 0.5));
    EXPECT_NEAR(volume(model.leafMeshes[0]), 23.0, 1e-9);  // a slab one unit thick
}

// A 2D hull of children of different colours is one shape, shown as the hull
// is (OpenSCAD's preview draws a hull in its own colour, not its children's):
// OpenSCAD 2021.01's `openscad -o x.svg` of
//   hull() { color("red") square(2); translate([5, 0]) color("blue") square(1); }
// is (0,0) (6,0) (6,1) (2,2) (0,2), of area 10.
TEST(FlatParse, AFlatHullOfColouredChildrenIsOneShape) {
    const Tree t = parse(
        "hull() {\n\tcolor([1, 0, 0, 1]) {\n\t\tsquare(size = [2, 2], center = false);\n\t}\n"
        "\tmultmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\t\tcolor([0, 0, 1, 1]) {\n\t\t\tsquare(size = [1, 1], center = false);\n\t\t}\n\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_FALSE(t.leaves[0].color.has_value());
    const model::Model model = model::buildModel(t);
    EXPECT_EQ(model.bounds.min, glm::dvec3(0, 0, -0.5));
    EXPECT_EQ(model.bounds.max, glm::dvec3(6, 2, 0.5));
    EXPECT_NEAR(volume(model.leafMeshes[0]), 10.0, 1e-9);
}

TEST(FlatParse, HullOfADifferenceHullsItsExactResult) {
    // A cube with its top half cut away: the hull is the remaining 2 x 2 x 1 box.
    const Tree t = parse(
        "hull() { difference() { cube(size = 2); multmatrix([[1, 0, 0, -1], [0, 1, 0, -1], [0, 0, 1, 1], "
        "[0, 0, 0, 1]]) cube(size = 4); } }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const auto& h = std::get<Hull>(t.leaves[0].primitive);
    ASSERT_EQ(h.parts.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Exact>(h.parts[0].primitive));
    const model::Model model = model::buildModel(t);
    EXPECT_NEAR(model.bounds.max.z, 1.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.x, 2.0, 1e-12);
}

// An L-shaped prism, the union of [0,6]x[0,2] and [0,2]x[0,5] raised to
// height 3, plus a centred 1 x 0.5 x 0.25 box: the L grows by half the box
// on every side, so its section is (6+1)(2+0.5) + (2+1)(5+0.5) - (2+1)(2+0.5)
// = 26.5 and the sum's volume 26.5 x 3.25.
constexpr double kSumOfLAndBox = 26.5 * 3.25;
const char* const kBox = "cube(size = [1, 0.5, 0.25], center = true);";

TEST(FlatParse, MinkowskiOfADifferenceSumsItsConvexParts) {
    const Tree t = parse(std::string("minkowski() { difference() { cube(size = [6, 5, 3]); "
                                     "multmatrix([[1, 0, 0, 2], [0, 1, 0, 2], [0, 0, 1, -1], [0, 0, 0, 1]]) "
                                     "cube(size = [10, 10, 5]); } ") +
                         kBox + " }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.unsupported.empty());
    const auto& sum = std::get<MinkowskiSum>(t.leaves[0].primitive);
    ASSERT_EQ(sum.operands.size(), 2u);
    EXPECT_TRUE(std::holds_alternative<Exact>(sum.operands[0]->leaves[0].primitive));
    const model::Model model = model::buildModel(t);
    EXPECT_NEAR(mesh::test::signedVolume(model.leafMeshes[0]), kSumOfLAndBox, 1e-9);
    EXPECT_NEAR(model.bounds.min.x, -0.5, 1e-12);
    EXPECT_NEAR(model.bounds.max.y, 5.25, 1e-12);
    EXPECT_NEAR(model.bounds.max.z, 3.125, 1e-12);
}

TEST(FlatParse, MinkowskiOfAPolyhedronSumsItsConvexParts) {
    // The same L, written as a polyhedron (its bottom and top as one face each).
    const Tree t = parse(std::string(
                             "minkowski() { polyhedron(points = [[0, 0, 0], [6, 0, 0], [6, 2, 0], [2, 2, 0], [2, 5, 0], "
                             "[0, 5, 0], [0, 0, 3], [6, 0, 3], [6, 2, 3], [2, 2, 3], [2, 5, 3], [0, 5, 3]], "
                             "faces = [[5, 4, 3, 2, 1, 0], [6, 7, 8, 9, 10, 11], [0, 1, 7, 6], [1, 2, 8, 7], "
                             "[2, 3, 9, 8], [3, 4, 10, 9], [4, 5, 11, 10], [5, 0, 6, 11]]); ") +
                         kBox + " }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<MinkowskiSum>(t.leaves[0].primitive));
    const model::Model model = model::buildModel(t);
    EXPECT_TRUE(mesh::checkMesh(model.leafMeshes[0]).ok());
    EXPECT_NEAR(mesh::test::signedVolume(model.leafMeshes[0]), kSumOfLAndBox, 1e-9);
    // The same sum again is answered by the cache.
    const std::size_t hits = exact::exactCacheHits();
    const model::Model again = model::buildModel(t);
    EXPECT_EQ(exact::exactCacheHits(), hits + 1);
    EXPECT_EQ(again.leafMeshes[0].triangles.size(), model.leafMeshes[0].triangles.size());
}

TEST(FlatParse, MinkowskiOfConvexSolidsStaysAUnionOfHulls) {
    // Cubes, spheres, cylinders and hulls are convex by construction: no CPU boolean.
    const Tree t = parse(std::string("minkowski() { union() { cube(size = 1); "
                                     "multmatrix([[1, 0, 0, 3], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                                     "sphere(r = 1); } ") +
                         kBox + " }\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    for (const Leaf& leaf : t.leaves) EXPECT_TRUE(std::holds_alternative<Hull>(leaf.primitive));
}

TEST(FlatParse, HullOfFlatShapesIsAFlatHull) {
    const Tree t = parse("hull() { square(size = 2); multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], "
                         "[0, 0, 0, 1]]) circle(r = 1); }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.isFlat());
    const FlatTree& s = std::get<FlatSlab>(t.leaves[0].primitive).shape;
    EXPECT_EQ(node(s, s.root).op, FlatOp::Hull);
    EXPECT_EQ(node(s, s.root).children.size(), 2u);
}

TEST(FlatParse, ResizeScalesTheBoxOfItsLeavesTogether) {
    // Two cubes side by side, resized to 10 along x with the other axes auto:
    // the box [0, 6] x [0, 2] x [0, 2] scales by 10/6 on every axis, then the
    // outer translate places it.
    const Tree t = parse(
        "multmatrix([[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
        "\tresize(newsize = [10,0,0], auto = [1,1,1], convexity = 0) {\n"
        "\t\tcube(size = 2);\n"
        "\t\tmultmatrix([[1, 0, 0, 4], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(size = 2);\n"
        "\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 2u);
    ASSERT_EQ(t.resizes.size(), 1u);
    EXPECT_EQ(t.resizes[0].leaves.size(), 2u);
    const model::Model model = model::buildModel(t);
    EXPECT_NEAR(model.bounds.min.x, 5.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.x, 15.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.y, 2.0 * 10.0 / 6.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.z, 2.0 * 10.0 / 6.0, 1e-12);
    // The gap between the cubes scales with them.
    EXPECT_NEAR(mesh::boundsOf(model.leafMeshes[1]).min.x, 5.0 + 4.0 * 10.0 / 6.0, 1e-12);
}

TEST(FlatParse, ResizeOfADifferenceTakesTheBoxOfItsExactResult) {
    // A 4 x 2 x 2 block less everything beyond x = 2: the result is a 2-cube,
    // so a resize to 6 along x (auto elsewhere) scales by 3, not 1.5.
    const Tree t = parse("resize(newsize = [6,0,0], auto = [1,1,1]) difference() { cube(size = [4, 2, 2]); "
                         "multmatrix([[1, 0, 0, 2], [0, 1, 0, -1], [0, 0, 1, -1], [0, 0, 0, 1]]) cube(size = [3, 4, 4]); }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Exact>(t.leaves[0].primitive));
    ASSERT_EQ(t.resizes.size(), 1u);
    const model::Model model = model::buildModel(t);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(model.bounds.min[i], 0.0, 1e-12) << i;
        EXPECT_NEAR(model.bounds.max[i], 6.0, 1e-12) << i;
    }
}

TEST(FlatParse, ProjectionReadsSolidsIntoATreeOfTheirOwn) {
    // In an extrusion: a cut of a difference (a section is the difference of
    // the sections), with an extrusion inside the solid subtree.
    const Tree t = parse(
        "linear_extrude(height = 1) {\n\tprojection(cut = true, convexity = 0) {\n"
        "\t\tdifference() { sphere(r = 5); linear_extrude(height = 20, center = true) circle(r = 1); }\n"
        "\t}\n}\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const FlatTree& s = std::get<LinearExtrude>(t.leaves[0].primitive).shape;
    ASSERT_EQ(s.shapes.size(), 1u);
    const auto& cut = std::get<Projection>(s.shapes[0]);
    EXPECT_TRUE(cut.cut);
    ASSERT_TRUE(cut.solid);
    EXPECT_EQ(cut.solid->leaves.size(), 2u);  // the sphere and the extruded circle
    EXPECT_EQ(cut.solid->nodes[static_cast<std::size_t>(cut.solid->root)].kind, NodeKind::Union);
    // Outside an extrusion, a projection is a flat result.
    const Tree shadowed = parse(
        "projection(cut = false) { multmatrix([[1, 0, 0, 9], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(size = 2); }\n");
    ASSERT_EQ(shadowed.leaves.size(), 1u);
    const FlatTree& slab = std::get<FlatSlab>(shadowed.leaves[0].primitive).shape;
    const auto& shadow = std::get<Projection>(slab.shapes.at(0));
    EXPECT_FALSE(shadow.cut);
    EXPECT_EQ(shadow.solid->leaves.at(0).transform[3][0], 9.0);  // placed inside the projection's frame
}

TEST(FlatParse, TheShadowOfADifferenceIsItsExactResults) {
    // A 2 x 2 block bored through by a pentagon (a cylinder of r 0.5 has 5
    // fragments): its shadow is the square less the pentagon.
    const Tree t = parse("linear_extrude(height = 1) projection() difference() { cube(size = 2, center = true); "
                         "cylinder(h = 4, r = 0.5, center = true); }\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_TRUE(t.unsupported.empty());
    const FlatTree& s = std::get<LinearExtrude>(t.leaves[0].primitive).shape;
    const auto& shadow = std::get<Projection>(s.shapes.at(0));
    ASSERT_EQ(shadow.solid->leaves.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<Exact>(shadow.solid->leaves[0].primitive));
    const model::Model model = model::buildModel(t);
    const double pentagon = 0.5 * 5 * 0.25 * std::sin(2 * 3.14159265358979323846 / 5);
    EXPECT_NEAR(volume(model.leafMeshes[0]), 4.0 - pentagon, 1e-4);  // Clipper's grid: within a few 2^-16
}

TEST(FlatParse, TheNewerDialectsSlantedExtrusionMovesTheTopAlongV) {
    // height is the length along v: the top of a 4 x 4 square lies 8 up and
    // 6 across, and the prism keeps the square's area at every height.
    const Tree t = parse("linear_extrude(height = 10, v = [ 0.6, 0, 0.8], center = true, $fn = 0, $fa = 12, $fs = 2) "
                         "square(size = [4, 4], center = true);\n");
    ASSERT_EQ(t.leaves.size(), 1u);
    const auto& e = std::get<LinearExtrude>(t.leaves[0].primitive);
    EXPECT_NEAR(e.direction.x, 0.6, 1e-15);
    EXPECT_NEAR(e.direction.z, 0.8, 1e-15);
    const model::Model model = model::buildModel(t);
    EXPECT_NEAR(model.bounds.min.z, -4.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.z, 4.0, 1e-12);
    EXPECT_NEAR(model.bounds.min.x, -2.0 - 3.0, 1e-12);
    EXPECT_NEAR(model.bounds.max.x, 2.0 + 3.0, 1e-12);
    EXPECT_NEAR(volume(model.leafMeshes[0]), 16.0 * 8.0, 1e-9);
}

TEST(FlatParse, AnExactResultIsNotEvaluatedAgainWhenAnEditLeavesItAlone) {
    const std::string shared =
        "hull() { difference() { sphere(r = 3); multmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 2], [0, 0, 0, 1]]) "
        "cube(size = 6, center = true); } }\n";
    const Tree before = parse(shared + "cube(size = 1);\n");
    const Tree after = parse(shared + "multmatrix([[1, 0, 0, 9], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cylinder(h = 3);\n");
    const model::Model first = model::buildModel(before);
    const std::size_t hits = exact::exactCacheHits();
    const model::Model second = model::buildModel(after);
    EXPECT_EQ(exact::exactCacheHits(), hits + 1);
    EXPECT_EQ(first.leafMeshes[0].positions, second.leafMeshes[0].positions);
    EXPECT_EQ(first.leafMeshes[0].triangles, second.leafMeshes[0].triangles);
}
