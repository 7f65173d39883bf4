#pragma once
// A scene whose tree is one CSG product (one intersection or difference of
// leaves, or a single leaf), in the form OpenCSG takes it: one triangle list
// per leaf, marked intersected or subtracted. Scenes with unions are not
// products (OpenCSG would need them normalised first) and say so.

#include <string>
#include <vector>

#include "strata/geometry/Model.h"
#include "strata/scene/Tree.h"

namespace strata::bench {

struct ProductOperand {
    std::vector<float> positions;  // world space, x y z per vertex, 3 vertices per triangle
    bool subtract = false;
    bool convex = true;            // cube, sphere, cylinder; polyhedra and imports count as non-convex
};

struct CsgProduct {
    std::vector<ProductOperand> operands;  // the leaves' meshes from the same geometry::Model strata draws
    geometry::Bounds bounds;               // of every operand's vertices
    std::string notProduct;                // non-empty: why the tree is no product, and operands is empty
};

CsgProduct csgProduct(const scene::Tree& tree, const geometry::Model& model);

}  // namespace strata::bench
