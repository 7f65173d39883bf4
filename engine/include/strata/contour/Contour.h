#pragma once
// Contouring of a tri-dexel image (Dexels.h) into a closed triangle mesh.

#include <functional>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/contour/Dexels.h"
#include "strata/contour/Planes.h"
#include "strata/mesh/Mesh.h"

namespace strata::contour {

// The boundary of the sampled solid: closed, 2-manifold, every triangle
// counter-clockwise seen from outside, no degenerate triangles. Sharp edges
// and corners of the solid are kept where a cell's crossings show them.
// Reports progress (core/Progress.h) per slab of cells. Throws strata::Error
// on an inconsistent image (a ray that ends inside, crossings out of order).
//
// With `planes` (the planes every face of the solid lies on), a patch whose
// crossings' planes meet in one point on the solid's faces puts its vertex
// there, and the flat regions that result are merged into few triangles: a
// flat face keeps the vertices of its outline, a sharp edge between two
// planes those at its ends, and the surface stays the same set of points.
// The merge reports its progress after each pass ("contour: flat regions",
// vertices removed of the contour's) and may be stopped there.
//
// A contour rebuilt on the planes can cross itself where two sheets of the
// solid lie within a cell or two of each other, or where a sharp edge's
// vertices, moved onto the edge, pass each other. With `findTangles`, the
// merged mesh is handed to it, and where it answers with places (boxes in
// world space around where triangles cross), the vertices near them go to
// their crossings' means, off their planes, and the merge runs again, the
// reach growing in up to four rounds, then a fifth that moves every vertex
// (the contour of crossings' means, much larger); the mesh returned is
// the one last handed to `findTangles`, whatever its answer was, which the
// caller keeps if it wants to know. The caller decides what crossing
// means for the file it writes (the export rounds to floats first and asks
// the exact room's predicates); this room has none of its own.
using FindTangles = std::function<std::vector<mesh::Bounds>(const mesh::Mesh&)>;

mesh::Mesh contour(const Dexels& dexels, const PlaneTable* planes = nullptr, const FindTangles& findTangles = {});

// A part of the solid, or a gap in it, that lies between two grid points
// along a ray: no grid point sees it, so the contour loses it (a wall
// vanishes, a slot closes) while the mesh stays closed.
struct FeatureBelowGrid {
    bool wall = true;          // solid between two crossings; else a gap
    double thickness = 0.0;    // along the ray, the thinnest such feature the image holds
    glm::dvec3 where{0.0};     // the middle of one lost feature, world space
};

// The thinnest feature the grid loses, if any. Counted only where the two
// crossings face each other, their normals within 20 degrees of opposite
// (a slab, not the tip of a wedge, whose sharp edge the contour rebuilds),
// and both face along the ray within 60 degrees (their normals' component
// along it above one half; not the sliver a ray clips off a curved surface
// where it grazes it). Every slab thinner than a cell is crossed that way
// along at least one of the three axes.
std::optional<FeatureBelowGrid> featureBelowGrid(const Dexels& dexels);

}  // namespace strata::contour
