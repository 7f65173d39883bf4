#pragma once
// Tri-dexel images of solids whose ray crossings have closed forms (or, for
// the torus, a bracketed root search): the contouring's input written
// independently of any mesh, so its output can be checked against the solid.

#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "strata/contour/Dexels.h"

namespace strata::contour::test {

// One stretch of a ray inside the solid: world coordinates along the ray's
// axis where it enters and leaves, and the outward normals there.
struct Span {
    double in = 0.0, out = 0.0;
    glm::dvec3 inNormal{0.0}, outNormal{0.0};
};
using Spans = std::vector<Span>;

class Solid {
public:
    virtual ~Solid() = default;
    // The spans, in order, of the ray along `axis` through `point` (whose
    // coordinate along `axis` is ignored).
    virtual Spans along(int axis, const glm::dvec3& point) const = 0;
    // Whether `p` is inside (for counting the sign patterns a test made).
    virtual bool contains(const glm::dvec3& p) const = 0;
};
using SolidPtr = std::shared_ptr<const Solid>;

SolidPtr box(const glm::dvec3& low, const glm::dvec3& high);
// A box of half sizes `half` about `center`, its axes the columns of `rotation`.
SolidPtr orientedBox(const glm::dvec3& center, const glm::dmat3& rotation, const glm::dvec3& half);
SolidPtr sphere(const glm::dvec3& center, double radius);
// About `center`, around the z axis: the tube of radius `minor` about the
// circle of radius `major`.
SolidPtr torus(const glm::dvec3& center, double major, double minor);
SolidPtr unite(std::vector<SolidPtr> parts);
SolidPtr subtract(SolidPtr from, SolidPtr cut);

// A grid of spacing `spacing` holding [low, high] with two cells to spare on
// every side, its planes off `low` by odd fractions of a cell (so faces at
// `low` are not on grid planes).
DexelGrid gridAround(const glm::dvec3& low, const glm::dvec3& high, double spacing);

Dexels sample(const Solid& solid, const DexelGrid& grid);

// A rotation by angles about x, then y, then z.
glm::dmat3 rotation(double x, double y, double z);

}  // namespace strata::contour::test
