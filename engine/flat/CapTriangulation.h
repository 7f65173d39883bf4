#pragma once
// Triangles covering a flat shape (outer outlines with holes), for the caps of
// extrusions: GLU's tessellator with the odd winding rule, so the result uses
// the outlines' own points and no others (where outlines touch, a point may be
// repeated; the mesh's vertex merging joins it).

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "strata/flat/Outlines.h"

namespace strata::flat::detail {

struct CapTriangles {
    std::vector<glm::dvec2> points;                   // the outlines' points, in order, then any GLU added
    std::vector<std::array<uint32_t, 3>> triangles;   // counter-clockwise seen from +z
};

CapTriangles triangulateCap(const Outlines& shape);

}  // namespace strata::flat::detail
