#pragma once
// The last step of an exact evaluation: corefinement cuts faces into many
// triangles, and a result's flat faces come out as runs of coplanar
// triangles with points that only the cutting needed. Here each such run
// becomes one polygon again, triangulated afresh in exact arithmetic, and
// the points no face needs are dropped: the fewest triangles for the
// solid's faces, as OpenSCAD's Nef polyhedra give, without building one.

#include "NefPolyhedra.h"

namespace strata::exact::detail {

// A face property of the exact evaluation's solids: the leaf triangle each
// face lies on (0: not known). Corefinement keeps it through the faces it
// splits and copies, so two faces with one known source lie in one plane
// and face one way without an exact test; the join below reads it and
// gives its output faces their region's.
inline constexpr const char* kFaceSource = "f:strata_source";

// Each face of `solid` a source of its own, none shared with any other solid.
void giveFacesSources(ExactSolid& solid);

// The same closed solid, point for point where points stay, with:
// - each edge-connected run of coplanar triangles that face one way (a
//   region) joined into one polygon, holes and all, and triangulated again
//   by a constrained Delaunay triangulation of its outline;
// - each point dropped that lies inside a region, or on a straight crease
//   between two regions with no other crease through it.
// A region with no point dropped keeps its triangles: any triangulation of
// a polygon on its own corners has as many.
// Throws std::runtime_error where the input is not a closed mesh whose
// faces enclose a volume (an outline that crosses itself, a triangle
// without area); callers fall back to Nef polyhedra there.
ExactSolid joinedCoplanarFaces(const ExactSolid& solid);

}  // namespace strata::exact::detail
