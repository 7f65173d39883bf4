#pragma once
// The box OpenSCAD fits its default view to (--viewall --autocenter), so that
// strata-render's default camera frames a scene as OpenSCAD's does.
//
// OpenSCAD 2021.01 normalises the tree into a sum of products and takes the
// union of the boxes of every product's positive terms, ignoring what the
// products subtract; its '#' and '%' parts count too. A leaf is a positive
// term exactly when it is the subtrahend of an even number of differences on
// its way up to the root, so no normalisation is needed to find them:
// difference(A, B) frames A only, difference(A, difference(B, C)) frames A and C.

#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::camera {

// The union of the world-space boxes of the leaves in positive position under
// tree.root and the background roots. `model` comes from model::buildModel(tree).
// Empty when no such leaf has a triangle.
mesh::Bounds viewBounds(const scene::Tree& tree, const model::Model& model);

}  // namespace strata::camera
