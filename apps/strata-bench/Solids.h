#pragma once
// Non-convex solids the bench builds in code, as OpenSCAD polyhedra (faces
// clockwise seen from outside), so they reach strata as scene::Polyhedron
// leaves: strata has no torus primitive and the bench reads no mesh files.

#include <glm/vec3.hpp>

#include "strata/scene/Tree.h"

namespace strata::bench {

// A torus around the Z axis: tube centre at `major` from the axis, tube
// radius `minor` < `major`; `segments` around the axis, `rings` around the
// tube, 2 * segments * rings triangles.
scene::Polyhedron torus(double major, double minor, int segments, int rings);

// A (p, q) = (2, 3) trefoil knot as a tube of radius `tube` around the curve
// ((2 + cos 3t) cos 2t, (2 + cos 3t) sin 2t, -sin 3t) * `scale`; `segments`
// along the curve, `rings` around the tube: 2 * segments * rings triangles.
// The tube stays clear of itself for tube < 0.5 * scale.
scene::Polyhedron torusKnot(double scale, double tube, int segments, int rings);

// The knot's centre curve at parameter t (period 2 pi).
glm::dvec3 torusKnotPoint(double scale, double t);

}  // namespace strata::bench
