#pragma once
// projection(): a solid subtree turned flat, as OpenSCAD 2021.01 does it.

#include "strata/flat/Outlines.h"
#include "strata/scene/Flat.h"

namespace strata::model {

// cut = false: the union of every triangle's shadow on z = 0, one child at a
// time and then together, through Clipper (the subtree holds only unions).
// cut = true: the section of the subtree's result by the plane z = 0, each
// leaf's section combined by the subtree's own booleans through Clipper (a
// section of a boolean is the boolean of the sections). A vertex exactly on
// the plane counts as above it, so a face lying in the plane with the solid
// below it is the section, and with the solid above it is not.
// The result is sanitized. Errors from the subtree's leaves name their
// positions.
flat::Outlines project(const scene::Projection& projection);

}  // namespace strata::model
