#pragma once
// hull() and minkowski() of convex solids: the convex hull of a point set
// through Qhull, as OpenSCAD 2021.01 takes CGAL's convex_hull_3 of its
// children's vertices. The hull's corners are input points, unmoved.

#include <vector>

#include <glm/vec3.hpp>

#include "strata/geometry/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::geometry {

// The closed, outward convex hull of `points`; empty when they span no
// volume (fewer than four, or all in one plane), as OpenSCAD makes nothing.
Mesh convexHull(const std::vector<glm::dvec3>& points);

// The hull of every part's vertices (world space), each moved by a vertex of
// every summand in turn.
Mesh tessellate(const scene::Hull& hull);

}  // namespace strata::geometry
