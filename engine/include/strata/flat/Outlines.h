#pragma once
// Flat geometry: closed outlines in the xy plane, OpenSCAD's Polygon2d.
//
// Outlines straight from a primitive may overlap or run either way round;
// once they have been through Clipper (`sanitized`), they do not cross, outer
// outlines run counter-clockwise and holes clockwise (`positive` says which),
// and their points lie on OpenSCAD's grid of 1/65536 units.

#include <vector>

#include <glm/vec2.hpp>

namespace strata::flat {

struct Outline {
    std::vector<glm::dvec2> points;  // closed: the last point joins the first
    bool positive = true;            // an outer outline (false: a hole)
};

struct Outlines {
    std::vector<Outline> outlines;
    bool sanitized = false;
    bool empty() const { return outlines.empty(); }
};

}  // namespace strata::flat
