#pragma once
// Primitives tessellated exactly as OpenSCAD 2021.01 does, vertex for vertex.
//
// Positions are bit-identical to OpenSCAD's (its exact-degree sin/cos). Its
// polygons are split as its preview renderer splits them: a quad (0,1,2,3)
// into (0,1,3) and (2,3,1), a polygon of five or more vertices into a fan
// around the average of its vertices (one extra vertex per such cap).
// Vertex order:
//   cube      the 8 corners: top face (x1,y1), (x2,y1), (x2,y2), (x1,y2), then
//             bottom (x1,y2), (x2,y2), (x2,y1), (x1,y1)
//   sphere    ring i (from the top) vertex k at index i*n + k, then the cap
//             centres (top, bottom) when n >= 5
//   cylinder  bottom circle (n vertices, or 1 apex when r1 == 0), top circle
//             (likewise for r2), then the cap centres when n >= 5
// Every result is closed and outward (counter-clockwise seen from outside).

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::mesh {

// OpenSCAD's Calc::get_fragments_from_r: max(floor(fn), 3) when fn > 0, else
// ceil(max(min(360/fa, 2*pi*r/fs), 5)); 3 when r < 2^-20 or fn is inf/NaN.
// fa and fs below 0.01 count as 0.01, as OpenSCAD clamps them.
int fragmentsFromR(double r, const scene::Fragments& f);

// Each is empty where OpenSCAD makes nothing: a cube size <= 0, a sphere r <= 0,
// a cylinder h <= 0, a negative radius or both radii 0 (and infinite sizes).
// A fragment count that would need more than 2^24 vertices throws strata::Error.
Mesh tessellate(const scene::Cube& cube);
Mesh tessellate(const scene::Sphere& sphere);
Mesh tessellate(const scene::Cylinder& cylinder);
// Reverses OpenSCAD's clockwise faces and ear-clips n-gons in the plane of
// their Newell normal (non-convex faces come out right). Positions are the
// points as given, unused and duplicated ones included (buildModel merges and
// drops them). A face index outside the points throws strata::Error.
Mesh tessellate(const scene::Polyhedron& polyhedron);

}  // namespace strata::mesh
