#pragma once
// OpenSCAD's use of Clipper 6 (src/clipper-utils.cc in 2021.01), step for
// step: points scaled by 2^16 and truncated to integers, outlines cleaned
// after each operation, results read back with their orientation as the
// outline's sign.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "strata/flat/Outlines.h"

namespace strata::flat {

inline constexpr double kClipperScale = 65536.0;  // OpenSCAD's CLIPPER_SCALE, 2^16

// The grid cell of a point as Clipper sees it: truncated toward zero, as
// OpenSCAD's IntPoint(x * 2^16) does. Throws strata::Error past Clipper's range.
std::pair<std::int64_t, std::int64_t> gridPoint(const glm::dvec2& p);

enum class FlatBoolean { Union, Intersection, Difference };

// Outlines as Clipper sees them after an even-odd union: no crossings,
// outer outlines counter-clockwise, on the grid.
Outlines sanitize(const Outlines& shape);

// The boolean of the children, in order (the first is the minuend of a
// difference). A child may be empty. Intersections are taken pairwise, left
// to right, as OpenSCAD does.
Outlines apply(const std::vector<const Outlines*>& children, FlatBoolean op);

// OpenSCAD's Minkowski sum of flat shapes (ClipperUtils::applyMinkowski):
// each outline of the running sum convolved with each outline of the next
// shape as quads, the insides filled, all unioned. Absent children are skipped.
Outlines minkowski(const std::vector<const Outlines*>& children);

// OpenSCAD's projection(cut = false): each child's triangles (xy of each,
// turned counter-clockwise) unioned non-zero, then all children unioned with
// Clipper's strictly simple output.
Outlines shadow(const std::vector<std::vector<std::array<glm::dvec2, 3>>>& children);

enum class FlatJoin { Round, Miter, Square };

// ClipperOffset(miterLimit, arcTolerance * 2^16).Execute(amount * 2^16).
Outlines offset(const Outlines& shape, double amount, FlatJoin join, double miterLimit, double arcTolerance);

}  // namespace strata::flat
