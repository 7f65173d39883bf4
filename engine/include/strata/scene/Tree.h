#pragma once
// The CSG tree: leaves (primitive + transform + colour) under n-ary union,
// intersection and difference nodes. Knows nothing about meshes or GL.
//
// Storage is flat: nodes and leaves live in vectors and refer to each other by
// index, so a tree of a million leaves is two allocations, not a million.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "strata/core/Error.h"
#include "strata/scene/Flat.h"

namespace strata::scene {

struct Cube {
    glm::dvec3 size{1.0, 1.0, 1.0};
    bool center = false;
};

struct Sphere {
    double r = 1.0;
    Fragments fragments;
};

// A cylinder or a cone (r1 at the bottom, r2 at the top; either may be 0).
struct Cylinder {
    double h = 1.0;
    double r1 = 1.0;
    double r2 = 1.0;
    bool center = false;
    Fragments fragments;
};

// Faces index points; as OpenSCAD writes them, each face is clockwise seen from outside.
struct Polyhedron {
    std::vector<glm::dvec3> points;
    std::vector<std::vector<int>> faces;
};

// A mesh file (STL, OFF, OBJ, PLY); path already resolved against the .csg's folder.
struct Import {
    std::string path;
};

// linear_extrude(): the union of the flat children, swept up by `height`.
struct LinearExtrude {
    FlatTree shape;
    double height = 100.0;     // the length of the extrusion
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit vector (newer dialect's v): the top is moved by height * direction
    bool center = false;
    double twist = 0.0;        // degrees, over the whole height
    bool hasTwist = false;     // twist was written (its slice rule applies)
    int slices = 1;
    bool hasSlices = false;    // slices was written
    glm::dvec2 scale{1.0, 1.0};  // of the top, relative to the bottom
    Fragments fragments;
};

// rotate_extrude(): the union of the flat children (in the half plane x >= 0
// or x <= 0) swept about the z axis, the 2D y axis becoming z.
struct RotateExtrude {
    FlatTree shape;
    double angle = 360.0;      // degrees
    double start = 0.0;        // newer dialect: the first ring's angle from +x
    bool hasStart = false;     // false: 2021.01's rings (360: from -x, else from +x)
    Fragments fragments;
};

// A flat result outside any extrusion, shown as OpenSCAD's preview shows it:
// a slab one unit thick, z in [-0.5, 0.5].
struct FlatSlab {
    FlatTree shape;
};

// surface(): a height map (.dat text or a PNG image) as a solid; path already
// resolved against the .csg's folder.
struct Surface {
    std::string path;
    bool center = false;
    bool invert = false;
};

struct Leaf;

// hull() of solids, and minkowski() of convex ones: the convex hull of the
// vertices of every part, each moved by a vertex of every summand in turn; a
// Minkowski sum of convex solids is the hull of their vertex sums. Parts and
// summands are whole leaves with their own transforms, relative to the hull
// leaf, whose transform places the result (as OpenSCAD transforms a result:
// summands placed in the world would add their translations).
struct Hull {
    std::vector<Leaf> parts;
    std::vector<Leaf> summands;
};

// A difference or intersection whose geometry a node needs (a hull, resize or
// shadow of it): its subtree, read into a tree of its own, evaluated exactly
// into one mesh (exact::exactResult).
struct Exact {
    std::shared_ptr<const Tree> solid;
};

// minkowski() of solids that are not all convex by construction: each
// operand is a child's subtree (a union of leaves, any difference or
// intersection in it already an Exact leaf), read into a tree of its own,
// placed relative to the sum's leaf; model::minkowskiSum splits each into
// convex parts and joins the parts' sums exactly, as OpenSCAD does (an
// operand with no solid is left out of the sum, as OpenSCAD leaves it out).
struct MinkowskiSum {
    std::vector<std::shared_ptr<const Tree>> operands;
};

using Primitive = std::variant<Cube, Sphere, Cylinder, Polyhedron, Import, LinearExtrude, RotateExtrude, FlatSlab,
                               Surface, Hull, Exact, MinkowskiSum>;

// How a leaf is drawn besides its part in the CSG result (OpenSCAD's modifiers).
enum class Display {
    Normal,      // part of the CSG result
    Highlight,   // '#': part of the CSG result and also drawn translucent
    Background,  // '%': not part of the CSG result, drawn translucent
};

// One matrix of the chain a leaf's transform was multiplied from: the
// multmatrix() nodes above it, the innermost last (`previous` leads
// outward). Shared by the leaves under one node, never changed. The exact
// evaluation applies the chain step by step in exact arithmetic, as
// OpenSCAD transforms a child's result, so that faces flush before a
// rotation stay flush after it.
struct TransformStep {
    glm::dmat4 matrix{1.0};
    // Mutable only so that the destructor can unlink a chain it owns alone.
    mutable std::shared_ptr<const TransformStep> previous;

    // Lets go of the chain a step at a time: a million nested multmatrix()
    // make a chain a million steps long, too long to end by recursion.
    ~TransformStep();
};

struct Leaf {
    Primitive primitive;
    glm::dmat4 transform{1.0};          // object to world (to its resize(), hull or sum, inside one), column vectors
    std::optional<glm::dvec4> color;    // RGBA in [0,1]; outermost color() wins
    Display display = Display::Normal;
    SourceLocation where;               // the primitive's line in the input
    // The chain `transform` was multiplied from, in doubles: its innermost
    // step, whose `previous` lead outward; null for the identity or where
    // it is not known. Consumers check that the chain's product is
    // `transform` before trusting it.
    std::shared_ptr<const TransformStep> steps;
};

// resize(): the leaves under it are scaled together so that the box of the
// result takes `newsize` (0 keeps an axis; `autosize` axes follow the largest
// given one), then placed by `outer`. Their transforms are relative to the
// resize; model::buildModel applies these in order (an inner resize is
// listed before the one around it).
struct Resize {
    glm::dvec3 newsize{0.0};
    std::array<bool, 3> autosize{false, false, false};
    glm::dmat4 outer{1.0};     // the resize's own object-to-world (or to an enclosing resize)
    std::vector<int> leaves;   // indices into Tree::leaves
    SourceLocation where;
};

enum class NodeKind { Leaf, Union, Intersection, Difference };

struct Node {
    NodeKind kind = NodeKind::Union;
    int leaf = -1;               // index into Tree::leaves, for NodeKind::Leaf
    std::vector<int> children;   // indices into Tree::nodes, in input order
    SourceLocation where;
};

// A parsed scene. nodes[root] is the CSG result (an implicit union at top level).
// A Union with no children is the empty solid. Background ('%') subtrees are
// kept apart in `background`: they are drawn, but they are not in the CSG.
struct Tree {
    std::vector<Node> nodes;
    std::vector<Leaf> leaves;
    int root = -1;                    // -1: nothing at all
    std::vector<int> background;      // roots of '%' subtrees
    std::vector<Resize> resizes;      // innermost first

    std::vector<Warning> warnings;                // already formatted, one per line
    std::map<std::string, int> unsupported;      // node name -> how many were left out
    std::string source;                           // the input's path as given

    // The leaves reachable from `node` (indices into `leaves`, in depth-first
    // order; a leaf reached twice is listed twice). Out-of-range indices, as
    // a tree built in code may hold, are passed over.
    std::vector<int> leavesUnder(int node) const;

    // True when every leaf of the CSG result is a FlatSlab (and there is one):
    // OpenSCAD would call the model 2D.
    bool isFlat() const;

    // Convenience builders, used by tests and embedders that make trees in code.
    int addLeaf(Leaf leaf);                                 // returns the node index
    int addNode(NodeKind kind, std::vector<int> children);  // returns the node index
};

// The scene of one mesh file (STL, OBJ, OFF, PLY), as the apps open it: a
// single Import leaf of `path`, the root a union of it. The file is read
// later, by model::buildModel.
Tree meshFileTree(const std::string& path);

// The OpenSCAD name of a leaf's primitive: "cube", ..., "linear_extrude",
// "rotate_extrude", "surface", "hull" (a minkowski of convex parts is one or
// more hulls; of other solids, a "minkowski"); "2D shape" for a FlatSlab;
// "CSG result" for an Exact.
const char* primitiveName(const Primitive& primitive);

// Short name of a node kind: "union", "intersection", "difference", "leaf".
const char* kindName(NodeKind kind);

}  // namespace strata::scene
