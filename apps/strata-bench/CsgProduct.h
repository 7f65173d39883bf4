#pragma once
// A scene in the form OpenCSG takes it, as OpenSCAD 2021.01's preview hands
// it over: its CSG tree normalized into a sum of products (SumOfProducts.h),
// each leaf one triangle list with the convexity OpenSCAD would give it.
// A tree whose normalization goes past the element limit (twice the
// rendering limit) has no products and says so, as OpenSCAD draws nothing
// then; a sum of more primitives than the rendering limit keeps its
// products but says it would not be drawn, as OpenSCAD turns OpenCSG off
// then ("Normalized tree has N elements! OpenCSG rendering has been
// disabled.").

#include <cstddef>
#include <string>
#include <vector>

#include "SumOfProducts.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::bench {

struct ProductLeaf {
    std::vector<float> positions;  // world space, x y z per vertex, 3 vertices per triangle; empty if in no product
    bool convex = true;            // cube, sphere, cylinder, hull; polyhedra, extrusions and imports count as non-convex
    // OpenSCAD's: 1 for cube, sphere, cylinder and hull; for the others the
    // `convexity = N` written on the leaf's line of the .csg, else 1.
    unsigned convexity = 1;
};

struct CsgProducts {
    std::vector<ProductLeaf> leaves;  // one per Tree::leaves, from the same model::Model strata draws
    SumOfProducts sum;                // products of indices into `leaves`
    mesh::Bounds bounds;          // of the leaves in any product
    std::string unavailable;          // non-empty: OpenSCAD would draw nothing with OpenCSG, and why
};

// `renderingLimit`: OpenSCAD's "Turn off rendering at ... elements".
CsgProducts csgProducts(const scene::Tree& tree, const model::Model& model,
                        std::size_t renderingLimit = kOpenScadRenderingLimit);

// The `convexity = N` argument on one line of a .csg, else 1 (OpenSCAD's
// default; values below 1 become 1, as OpenSCAD makes them).
unsigned convexityOnLine(const std::string& line);

}  // namespace strata::bench
