#pragma once
// A CSG tree rewritten as a sum (union) of products, the form OpenCSG draws,
// by the rules OpenSCAD 2021.01's preview applies (Goldfeather et al., "Near
// real-time CSG rendering using tree normalization and geometric pruning",
// 1989):
//
//  * The n-ary tree becomes a binary one, each operation folded from the
//    left: union(a, b, c) is (a + b) + c. While it is built, an empty operand
//    drops out (x + 0 = x, x - 0 = x, x * 0 = 0, 0 - x = 0), an intersection
//    whose operands' boxes do not overlap is empty, and a difference whose
//    subtrahend's box misses the minuend's is its minuend (pruning).
//  * The binary tree is rewritten top down, left before right, with
//      x - (y + z) -> (x - y) - z        (x + y) - z -> (x - z) + (y - z)
//      x * (y + z) -> (x * y) + (x * z)  (x + y) * z -> (x * z) + (y * z)
//      x - (y * z) -> (x - y) + (x - z)  (x - y) * z -> (x * z) - y
//      x * (y * z) -> (x * y) * z
//      x - (y - z) -> (x - y) + (x * z)
//      x * (y - z) -> (x * y) - z
//    A rewritten subtree is shared, not copied, by the terms that use it, as
//    in OpenSCAD, so rewriting it once rewrites it everywhere.
//  * Every visit of an operation counts one element; past the limit
//    (twice OpenSCAD's "Turn off rendering at" preference: 200,000 by
//    default) the rewriting stops and nothing is drawn (OpenSCAD:
//    "Normalized tree is growing past 200000 elements. Aborting
//    normalization.", then "CSG normalization resulted in an empty tree").
//  * The normalized tree is read left to right into products: a leaf under
//    a union starts a new product once the current one has an intersected
//    leaf; a leaf reached as a difference's right operand is subtracted, as
//    an intersection's right operand intersected.
//
// Highlighted ('#') leaves are part of the CSG result and stay in it (OpenSCAD
// also draws them once more, translucent, as products of their own: not done
// here); background ('%') subtrees are already out of scene::Tree's CSG.

#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/scene/Tree.h"

namespace strata::bench {

// OpenSCAD's "Turn off rendering at ... elements" preference, by default:
// a sum of more primitives than this is not drawn with OpenCSG
// (CsgProduct.h), and the normalization stops at twice as many elements.
constexpr std::size_t kOpenScadRenderingLimit = 100000;
constexpr std::size_t kOpenScadNormalizeLimit = 2 * kOpenScadRenderingLimit;

struct LeafBox {
    glm::dvec3 min, max;  // world space
};

struct NormalizedProduct {
    std::vector<int> intersections;  // indices into Tree::leaves, in drawing order
    std::vector<int> subtractions;
};

struct SumOfProducts {
    std::vector<NormalizedProduct> products;  // empty when the limit was reached or nothing is left
    std::size_t elements = 0;                 // operations the rewriting visited (OpenSCAD's count)
    bool gaveUp = false;                      // the count went past the limit
    std::size_t limit = kOpenScadNormalizeLimit;

    std::size_t primitives() const;  // leaves over all products
};

// `leafBoxes[i]`: the box of Tree::leaves[i], or nullopt where its geometry is
// empty. The CSG result from tree.root; an empty tree gives no products.
SumOfProducts sumOfProducts(const scene::Tree& tree, const std::vector<std::optional<LeafBox>>& leafBoxes,
                            std::size_t limit = kOpenScadNormalizeLimit);

}  // namespace strata::bench
