#pragma once
// Primitives tessellated exactly as OpenSCAD 2021.01 does, vertex for vertex.

#include "strata/geometry/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::geometry {

// OpenSCAD's Calc::get_fragments_from_r: max(floor(fn), 3) when fn > 0, else
// ceil(max(min(360/fa, 2*pi*r/fs), 5)); 3 when r < 2^-20.
int fragmentsFromR(double r, const scene::Fragments& f);

Mesh tessellate(const scene::Cube& cube);
Mesh tessellate(const scene::Sphere& sphere);       // empty when r <= 0
Mesh tessellate(const scene::Cylinder& cylinder);   // empty when degenerate
Mesh tessellate(const scene::Polyhedron& polyhedron);  // reverses OpenSCAD's clockwise faces, triangulates n-gons

}  // namespace strata::geometry
