#pragma once
// Extrusions of flat shapes, meshed as OpenSCAD 2021.01 meshes them
// (src/GeometryEvaluator.cc: extrudePolygon, rotatePolygon): the same vertices,
// the same diagonals on the side quads. Caps are triangulated by GLU (any
// triangulation of a planar cap is the same surface). The top cap and each
// ring reuse the side walls' points, so the result is closed even where
// OpenSCAD's own caps differ from its walls in the last bit.
//
// `shape` must be sanitized (model::evaluateFlat's result). Results are
// counter-clockwise seen from outside; zero-area triangles where rings meet
// the axis or collapse are left for dropDegenerateTriangles.

#include "strata/flat/Outlines.h"
#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::flat {

// OpenSCAD's slice count for the extrusion (Calc::get_helix_slices and friends).
int linearExtrudeSlices(const scene::LinearExtrude& extrude, const Outlines& shape);

mesh::Mesh linearExtrude(const scene::LinearExtrude& extrude, const Outlines& shape);

// Throws strata::Error (no position) when the shape has points on both sides of x = 0.
mesh::Mesh rotateExtrude(const scene::RotateExtrude& extrude, const Outlines& shape);

// A flat result as OpenSCAD's preview draws it: one unit thick, z in [-0.5, 0.5].
mesh::Mesh flatSlab(const Outlines& shape);

}  // namespace strata::flat
