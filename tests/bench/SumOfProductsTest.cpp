// strata-bench's normalization of a CSG tree into OpenSCAD 2021.01's sum of
// products (SumOfProducts.h), against products and element counts derived
// by hand from OpenSCAD's rules.
#include <gtest/gtest.h>

#include "CsgProduct.h"
#include "Scenes.h"
#include "SumOfProducts.h"
#include "strata/model/Model.h"

using namespace strata;
using bench::NormalizedProduct;

namespace {

// A tree of named leaves; every leaf's box is the same unit box unless set.
struct Builder {
    scene::Tree tree;
    std::vector<std::optional<bench::LeafBox>> boxes;

    int leaf(bench::LeafBox box = {glm::dvec3(0.0), glm::dvec3(1.0)}) {
        scene::Leaf l;
        l.primitive = scene::Cube{};
        boxes.push_back(box);
        return tree.addLeaf(std::move(l));
    }
    int emptyLeaf() {
        scene::Leaf l;
        l.primitive = scene::Cube{};
        boxes.push_back(std::nullopt);
        return tree.addLeaf(std::move(l));
    }
    int add(scene::NodeKind kind, std::vector<int> children) { return tree.addNode(kind, std::move(children)); }

    bench::SumOfProducts sum(int root, std::size_t limit = bench::kOpenScadNormalizeLimit) {
        tree.root = root;
        return bench::sumOfProducts(tree, boxes, limit);
    }
};

using K = scene::NodeKind;

// Leaf node index n is leaf n here: every leaf is added before any operation.
NormalizedProduct product(std::vector<int> intersections, std::vector<int> subtractions = {}) {
    return {std::move(intersections), std::move(subtractions)};
}

void expectProducts(const bench::SumOfProducts& sum, const std::vector<NormalizedProduct>& expected) {
    ASSERT_FALSE(sum.gaveUp);
    ASSERT_EQ(sum.products.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(sum.products[i].intersections, expected[i].intersections) << "product " << i;
        EXPECT_EQ(sum.products[i].subtractions, expected[i].subtractions) << "product " << i;
    }
}

}  // namespace

TEST(SumOfProducts, UnionMinusLeafIsOneProductPerUnionOperand) {
    // (A + B) - C -> (A - C) + (B - C)
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Difference, {b.add(K::Union, {a, bb}), c}));
    expectProducts(sum, {product({0}, {2}), product({1}, {2})});
    EXPECT_EQ(sum.elements, 3u);  // the difference (rewritten to a union), then each new difference
    EXPECT_EQ(sum.primitives(), 4u);
}

TEST(SumOfProducts, LeafMinusUnionSubtractsEveryOperand) {
    // A - (B + C) -> (A - B) - C
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Difference, {a, b.add(K::Union, {bb, c})}));
    expectProducts(sum, {product({0}, {1, 2})});
    EXPECT_EQ(sum.elements, 2u);
}

TEST(SumOfProducts, NaryDifferenceIsOneProduct) {
    // difference(A, B, C) folds to (A - B) - C already.
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Difference, {a, bb, c}));
    expectProducts(sum, {product({0}, {1, 2})});
    EXPECT_EQ(sum.elements, 2u);
}

TEST(SumOfProducts, IntersectionDistributesOverUnion) {
    // A * (B + C) -> (A * B) + (A * C)
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Intersection, {a, b.add(K::Union, {bb, c})}));
    expectProducts(sum, {product({0, 1}), product({0, 2})});
    EXPECT_EQ(sum.elements, 3u);
}

TEST(SumOfProducts, UnionTimesUnionIsFourProducts) {
    // (A + B) * (C + D) -> ((A * C) + (B * C)) + ((A * D) + (B * D)): the
    // root, each half, each of the four products: 7 elements.
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf(), d = b.leaf();
    const bench::SumOfProducts sum =
        b.sum(b.add(K::Intersection, {b.add(K::Union, {a, bb}), b.add(K::Union, {c, d})}));
    expectProducts(sum, {product({0, 2}), product({1, 2}), product({0, 3}), product({1, 3})});
    EXPECT_EQ(sum.elements, 7u);
}

TEST(SumOfProducts, LeafMinusDifferenceKeepsWhatTheInnerOneCut) {
    // A - (B - C) -> (A - B) + (A * C)
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Difference, {a, b.add(K::Difference, {bb, c})}));
    expectProducts(sum, {product({0}, {1}), product({0, 2})});
}

TEST(SumOfProducts, LeafMinusIntersectionIsTwoProducts) {
    // A - (B * C) -> (A - B) + (A - C)
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf();
    const bench::SumOfProducts sum = b.sum(b.add(K::Difference, {a, b.add(K::Intersection, {bb, c})}));
    expectProducts(sum, {product({0}, {1}), product({0}, {2})});
}

TEST(SumOfProducts, NestedDifferenceUnderIntersection) {
    // (A - B) * (C + D) -> ((A * C) - B) + ((A * D) - B)
    Builder b;
    const int a = b.leaf(), bb = b.leaf(), c = b.leaf(), d = b.leaf();
    const bench::SumOfProducts sum =
        b.sum(b.add(K::Intersection, {b.add(K::Difference, {a, bb}), b.add(K::Union, {c, d})}));
    expectProducts(sum, {product({0, 2}, {1}), product({0, 3}, {1})});
}

TEST(SumOfProducts, DisjointBoxesArePruned) {
    Builder b;
    const bench::LeafBox far{glm::dvec3(10.0), glm::dvec3(11.0)};
    const int a = b.leaf(), bb = b.leaf(far), c = b.leaf(), empty = b.emptyLeaf();
    // (A * B) + C: A * B is empty, C is left.
    expectProducts(b.sum(b.add(K::Union, {b.add(K::Intersection, {a, bb}), c})), {product({2})});
    // A - B: B misses A, so A alone.
    expectProducts(b.sum(b.add(K::Difference, {a, bb})), {product({0})});
    // A - empty, empty + C: the empty leaf drops out.
    expectProducts(b.sum(b.add(K::Union, {b.add(K::Difference, {a, empty}), b.add(K::Union, {empty, c})})),
                   {product({0}), product({2})});
    // A * B alone: nothing at all.
    const bench::SumOfProducts nothing = b.sum(b.add(K::Intersection, {a, bb}));
    EXPECT_FALSE(nothing.gaveUp);
    EXPECT_TRUE(nothing.products.empty());
}

TEST(SumOfProducts, ElementCountOfAUnionChainAndTheLimit) {
    // union() of n leaves folds to n - 1 unions, each visited once.
    auto chain = [](int n, std::size_t limit) {
        Builder b;
        std::vector<int> leaves;
        for (int i = 0; i < n; ++i) leaves.push_back(b.leaf());
        return b.sum(b.add(K::Union, leaves), limit);
    };
    const bench::SumOfProducts atLimit = chain(11, 10);
    EXPECT_FALSE(atLimit.gaveUp);
    EXPECT_EQ(atLimit.elements, 10u);
    EXPECT_EQ(atLimit.products.size(), 11u);
    const bench::SumOfProducts past = chain(12, 10);
    EXPECT_TRUE(past.gaveUp);
    EXPECT_EQ(past.elements, 11u);
    EXPECT_TRUE(past.products.empty());
    EXPECT_EQ(chain(1000, bench::kOpenScadNormalizeLimit).elements, 999u);

    // The same as nested union() nodes of two children each, 50,000 deep:
    // the same count, and no recursion as deep as the tree.
    Builder b;
    int node = b.leaf();
    for (int i = 1; i < 50000; ++i) node = b.add(K::Union, {node, b.leaf()});
    const bench::SumOfProducts nested = b.sum(node);
    EXPECT_FALSE(nested.gaveUp);
    EXPECT_EQ(nested.elements, 49999u);
    EXPECT_EQ(nested.products.size(), 50000u);
}

TEST(SumOfProducts, BlowupSceneGrowsAsTwoToTheK) {
    camera::Camera base;
    {
        const bench::BenchScene scene = bench::makeScene("blowup", 4, 1, base);
        const bench::CsgProducts products = bench::csgProducts(scene.tree, model::buildModel(scene.tree));
        ASSERT_TRUE(products.unavailable.empty()) << products.unavailable;
        ASSERT_EQ(products.sum.products.size(), 16u);
        for (const NormalizedProduct& p : products.sum.products) {
            EXPECT_EQ(p.intersections.size(), 4u);
            EXPECT_TRUE(p.subtractions.empty());
        }
        EXPECT_EQ(products.sum.primitives(), 64u);
    }
    {
        // 2^20 products of 20: far past OpenSCAD's limit, which stops it early.
        const bench::BenchScene scene = bench::makeScene("blowup", 20, 1, base);
        const bench::CsgProducts products = bench::csgProducts(scene.tree, model::buildModel(scene.tree));
        EXPECT_TRUE(products.sum.gaveUp);
        EXPECT_EQ(products.sum.elements, bench::kOpenScadNormalizeLimit + 1);
        EXPECT_NE(products.unavailable.find("200000"), std::string::npos) << products.unavailable;
        EXPECT_TRUE(products.sum.products.empty());
    }
}

TEST(SumOfProducts, ConvexityFromTheCsgLine) {
    EXPECT_EQ(bench::convexityOnLine("polyhedron(points = [[0, 0, 0]], faces = [[0, 1, 2]], convexity = 3);"), 3u);
    EXPECT_EQ(bench::convexityOnLine("linear_extrude(height = 3, center = false, convexity = 10, scale = [1, 1]) {"),
              10u);
    EXPECT_EQ(bench::convexityOnLine("import(file = \"a.stl\", convexity=4);"), 4u);
    EXPECT_EQ(bench::convexityOnLine("import(file = \"a.stl\", convexity = 0);"), 1u);
    EXPECT_EQ(bench::convexityOnLine("import(file = \"a.stl\", myconvexity = 5);"), 1u);
    EXPECT_EQ(bench::convexityOnLine("cube(size = [1, 1, 1], center = false);"), 1u);
}

TEST(SumOfProducts, RenderingLimitAndTwiceItForTheNormalization) {
    // OpenSCAD's "Turn off rendering at N elements": more than N primitives
    // over all products turn OpenCSG off; the normalization stops past 2N.
    auto cubes = [](scene::NodeKind kind, int n) {
        scene::Tree tree;
        std::vector<int> leaves;
        for (int i = 0; i < n; ++i) {
            scene::Leaf leaf;
            leaf.primitive = scene::Cube{};
            leaves.push_back(tree.addLeaf(std::move(leaf)));
        }
        tree.root = tree.addNode(kind, leaves);
        return tree;
    };
    {
        // difference() of 12 cubes: one product of 12, after 11 elements.
        const scene::Tree tree = cubes(K::Difference, 12);
        const model::Model model = model::buildModel(tree);
        const bench::CsgProducts over = bench::csgProducts(tree, model, 11);
        EXPECT_FALSE(over.sum.gaveUp);
        EXPECT_EQ(over.sum.elements, 11u);
        EXPECT_EQ(over.sum.primitives(), 12u);
        EXPECT_NE(over.unavailable.find("OpenCSG off"), std::string::npos) << over.unavailable;
        const bench::CsgProducts at = bench::csgProducts(tree, model, 12);
        EXPECT_TRUE(at.unavailable.empty()) << at.unavailable;
        EXPECT_EQ(at.sum.products.size(), 1u);
    }
    {
        // union() of n cubes: n - 1 elements; with N = 5 the normalization
        // stops past 10, so 11 cubes normalize (and are too many to draw)
        // and 12 give up.
        const scene::Tree eleven = cubes(K::Union, 11), twelve = cubes(K::Union, 12);
        const bench::CsgProducts a = bench::csgProducts(eleven, model::buildModel(eleven), 5);
        EXPECT_FALSE(a.sum.gaveUp);
        EXPECT_EQ(a.sum.elements, 10u);
        EXPECT_NE(a.unavailable.find("OpenCSG off"), std::string::npos) << a.unavailable;
        const bench::CsgProducts b = bench::csgProducts(twelve, model::buildModel(twelve), 5);
        EXPECT_TRUE(b.sum.gaveUp);
        EXPECT_EQ(b.sum.elements, 11u);
        EXPECT_NE(b.unavailable.find("gave up"), std::string::npos) << b.unavailable;
    }
}
