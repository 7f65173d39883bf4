#pragma once
// The modules of OpenSCAD's CSG export, in one table: each name the parser
// knows, and what it is. The parser looks a statement's name up once
// (moduleNamed) and every family of statements switches on the module:
// solids, 2D shapes and what reads a 2D subtree, booleans and transforms,
// and the nodes that gather their children into other leaves.

#include <string_view>

namespace strata::scene {

enum class Module {
    // Booleans and transforms: a node of the tree, or its children's context.
    Group, Union, Render, Assign, Intersection, Difference, Multmatrix, Color,
    // Gathering nodes: their children become other leaves when they close.
    Hull, Minkowski, Resize, Projection,
    // 2D shapes, and the nodes that read a 2D subtree.
    Square, Circle, Polygon, Text, Offset, LinearExtrude, RotateExtrude,
    // Solids. import() is a solid or a 2D shape by its file's extension.
    Cube, Sphere, Cylinder, Polyhedron, Surface, Import,
    // Known to OpenSCAD but not drawn by strata: left out with a warning.
    Unsupported,
    // Any other name: an error.
    Unknown,
};

Module moduleNamed(std::string_view name);

// square, circle, polygon, text.
constexpr bool isFlatShapeModule(Module m) { return m >= Module::Square && m <= Module::Text; }
// cube, sphere, cylinder, polyhedron, surface (import() apart).
constexpr bool isSolidModule(Module m) { return m >= Module::Cube && m <= Module::Surface; }
// group, union, render, assign: a union whose single child may stand in its place.
constexpr bool isUnionModule(Module m) { return m >= Module::Group && m <= Module::Assign; }

}  // namespace strata::scene
