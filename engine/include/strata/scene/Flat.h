#pragma once
// Flat (2D) subtrees as the CSG export writes them: square, circle, polygon,
// text and 2D imports under 2D union / difference / intersection, multmatrix
// and offset. A FlatTree is a description, not geometry: model::evaluateFlat
// turns it into outlines exactly as OpenSCAD 2021.01 does, node by node.
//
// Storage is flat like the Tree's: nodes refer to their children by index,
// and a child always comes after its parent (nodes are appended as their
// statements begin), so evaluating from the last node to the first meets
// every child before its parent, with no recursion.

#include <array>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "strata/core/Error.h"

namespace strata::scene {

// OpenSCAD's special variables that choose the number of fragments of a circle.
struct Fragments {
    double fn = 0.0;   // $fn: fixed count when > 0
    double fa = 12.0;  // $fa: minimum angle, degrees
    double fs = 2.0;   // $fs: minimum edge length, world units
};

struct Square {
    glm::dvec2 size{1.0, 1.0};
    bool center = false;
};

struct Circle {
    double r = 1.0;
    Fragments fragments;
};

// Outlines index `points`; with no paths, the points themselves are the one outline.
struct Polygon {
    std::vector<glm::dvec2> points;
    std::vector<std::vector<int>> paths;
};

// text(): the arguments as the export writes them (script is the resolved tag).
struct Text {
    std::string text;
    double size = 10.0;
    double spacing = 1.0;
    std::string font;          // fontconfig pattern; empty: "Liberation Sans"
    std::string direction = "ltr";
    std::string language = "en";
    std::string script = "Latn";
    std::string halign = "left";
    std::string valign = "baseline";
    Fragments fragments;
};

// import() of a 2D file (DXF or SVG); path already resolved against the .csg's folder.
struct FlatImport {
    std::string path;
    std::string layer;                // DXF layer; empty: all layers
    glm::dvec2 origin{0.0, 0.0};
    double scale = 1.0;
    bool center = false;              // SVG (newer dialect)
    double dpi = 72.0;                // SVG
    Fragments fragments;
};

struct Tree;

// projection(): a solid subtree, read into a tree of its own (in the
// projection's frame), seen from above (cut = false: its shadow on z = 0) or
// cut by the plane z = 0 (cut = true).
struct Projection {
    bool cut = false;
    std::shared_ptr<const Tree> solid;
};

using FlatPrimitive = std::variant<Square, Circle, Polygon, Text, FlatImport, Projection>;

// offset(r = ...) rounds the corners; offset(delta = ...) keeps them sharp
// (miter joins) or, with chamfer = true, cuts them square.
struct Offset {
    enum class Join { Round, Miter, Square };
    Join join = Join::Round;
    double amount = 1.0;   // r or delta
    Fragments fragments;   // for Join::Round
};

enum class FlatOp {
    Shape,         // a primitive: FlatNode::shape indexes FlatTree::shapes
    Union,         // group, union, color, render: the union of the children
    Intersection,
    Difference,
    Transform,     // multmatrix: the union of the children, then the matrix's xy part
    Offset,        // the union of the children, offset
    Hull,          // the convex hull of the children's points
    Minkowski,     // the Minkowski sum of the children, through Clipper
    Resize,        // the union of the children, scaled to FlatNode::resize
    Empty,         // a child that gives no 2D geometry (a 3D object, an unsupported node)
};

struct FlatNode {
    FlatOp op = FlatOp::Union;
    int shape = -1;                // FlatOp::Shape: index into FlatTree::shapes
    glm::dmat4 matrix{1.0};        // FlatOp::Transform, as written (3D, applied to column vectors)
    Offset offset;                 // FlatOp::Offset
    glm::dvec2 newsize{0.0};       // FlatOp::Resize: 0 keeps an axis
    std::array<bool, 2> autosize{false, false};
    std::vector<int> children;     // indices into FlatTree::nodes, in input order
    SourceLocation where;
};

struct FlatTree {
    std::vector<FlatNode> nodes;
    std::vector<FlatPrimitive> shapes;
    int root = -1;  // -1: no geometry

    int add(FlatNode node);  // returns the node index
};

}  // namespace strata::scene
