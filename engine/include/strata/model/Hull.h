#pragma once
// hull() and minkowski() of convex solids: the convex hull of a point set
// through Qhull, as OpenSCAD 2021.01 takes CGAL's convex_hull_3 of its
// children's vertices. The hull's corners are input points, unmoved.

#include <vector>

#include <glm/vec3.hpp>

#include "strata/mesh/Mesh.h"
#include "strata/scene/Tree.h"

namespace strata::model {

// The closed, outward convex hull of `points`; empty when they span no
// volume (fewer than four, or all in one plane), as OpenSCAD makes nothing.
mesh::Mesh convexHull(const std::vector<glm::dvec3>& points);

// Every point of `a` moved by every point of `b`: the corners whose hull is
// the Minkowski sum of the hulls of `a` and `b`. Throws strata::Error
// ("minkowski: too many points ...") past 2^24 of them.
std::vector<glm::dvec3> pointSums(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b);

// The hull of every part's vertices, each moved by a vertex of every summand
// in turn, relative to the hull's leaf (its transform places the result).
// Empty where a summand makes no mesh: that choice of parts adds nothing.
mesh::Mesh tessellate(const scene::Hull& hull);

}  // namespace strata::model
