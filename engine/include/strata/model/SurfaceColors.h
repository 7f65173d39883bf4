#pragma once
// The colour of each triangle of a CSG result, from the leaf whose surface it
// lies on: what a coloured export (3MF) writes. A triangle of the exact
// result lies in a face of one of the leaves' meshes (a difference's cut is
// the subtracted leaf's surface), so its centroid is found on that leaf.

#include <optional>
#include <vector>

#include <glm/vec4.hpp>

#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::model {

// One RGBA per triangle of `result`: the colour of the first leaf (in tree
// order) whose mesh has a face holding the triangle's centroid, `fallback`
// for a leaf without color() or a triangle no leaf holds. Empty when no leaf
// of the tree has a colour (nothing to write).
// `reach` > 0: the result only approximates the leaves' faces (the image-space
// export): a face holds a centroid within `reach` of it, and the nearest such
// face decides.
std::vector<glm::vec4> surfaceColors(const mesh::Mesh& result, const scene::Tree& tree, const Model& model,
                                     const glm::vec4& fallback, double reach = 0.0);

}  // namespace strata::model
