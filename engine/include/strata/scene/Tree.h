#pragma once
// The CSG tree: leaves (primitive + transform + colour) under n-ary union,
// intersection and difference nodes. Knows nothing about meshes or GL.
//
// Storage is flat: nodes and leaves live in vectors and refer to each other by
// index, so a tree of a million leaves is two allocations, not a million.

#include <array>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "strata/core/Error.h"

namespace strata::scene {

// OpenSCAD's special variables that choose the number of fragments of a circle.
struct Fragments {
    double fn = 0.0;   // $fn: fixed count when > 0
    double fa = 12.0;  // $fa: minimum angle, degrees
    double fs = 2.0;   // $fs: minimum edge length, world units
};

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

using Primitive = std::variant<Cube, Sphere, Cylinder, Polyhedron, Import>;

// How a leaf is drawn besides its part in the CSG result (OpenSCAD's modifiers).
enum class Display {
    Normal,      // part of the CSG result
    Highlight,   // '#': part of the CSG result and also drawn translucent
    Background,  // '%': not part of the CSG result, drawn translucent
};

struct Leaf {
    Primitive primitive;
    glm::dmat4 transform{1.0};          // object to world, applied to column vectors
    std::optional<glm::dvec4> color;    // RGBA in [0,1]; outermost color() wins
    Display display = Display::Normal;
    SourceLocation where;               // the primitive's line in the input
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

    std::vector<Warning> warnings;                // already formatted, one per line
    std::map<std::string, int> unsupported;      // node name -> how many were left out
    std::string source;                           // the input's path as given

    // Convenience builders, used by tests and embedders that make trees in code.
    int addLeaf(Leaf leaf);                                 // returns the node index
    int addNode(NodeKind kind, std::vector<int> children);  // returns the node index
};

// The scene of one mesh file (STL, OBJ, OFF, PLY), as the apps open it: a
// single Import leaf of `path`, the root a union of it. The file is read
// later, by geometry::buildModel.
Tree meshFileTree(const std::string& path);

// Short name of a node kind: "union", "intersection", "difference", "leaf".
const char* kindName(NodeKind kind);

}  // namespace strata::scene
