// Interval algebra and tree evaluation along one ray, checked case by case and
// against brute force: random interval lists and random trees, compared with
// the tree's membership evaluated point by point between all boundaries.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "strata/core/Error.h"
#include "strata/reference/IntervalCsg.h"

using namespace strata::reference;
using strata::scene::NodeKind;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Interval span(double begin, double end, int leaf) {
    return {begin, end, Surface{begin == -kInf ? -1 : leaf, -1, true}, Surface{end == kInf ? -1 : leaf, -1, false}};
}

bool contains(const IntervalList& list, double t) {
    return std::any_of(list.begin(), list.end(), [t](const Interval& x) { return x.begin < t && t < x.end; });
}

::testing::AssertionResult canonical(const IntervalList& list) {
    for (std::size_t i = 0; i < list.size(); ++i) {
        if (!(list[i].begin < list[i].end)) return ::testing::AssertionFailure() << "empty interval " << i;
        if (i > 0 && !(list[i - 1].end < list[i].begin)) {
            return ::testing::AssertionFailure() << "intervals " << i - 1 << " and " << i << " touch or overlap";
        }
    }
    return ::testing::AssertionSuccess();
}

}  // namespace

TEST(IntervalCsg, UnionOfTouchingIntervalsHasNoSurfaceWhereTheyMeet) {
    const IntervalList out = unite({span(1, 3, 0)}, {span(3, 5, 1)});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].begin, 1.0);
    EXPECT_EQ(out[0].end, 5.0);
    EXPECT_EQ(out[0].beginSurface.leaf, 0);
    EXPECT_EQ(out[0].endSurface.leaf, 1);
}

TEST(IntervalCsg, IntersectionStartsAtTheLaterEntry) {
    const IntervalList out = intersect({span(1, 4, 0), span(6, 9, 0)}, {span(2, 7, 1)});
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].begin, 2.0);
    EXPECT_EQ(out[0].beginSurface.leaf, 1);
    EXPECT_EQ(out[0].end, 4.0);
    EXPECT_EQ(out[0].endSurface.leaf, 0);
    EXPECT_EQ(out[1].begin, 6.0);
    EXPECT_EQ(out[1].end, 7.0);
    // Touching is not overlapping.
    EXPECT_TRUE(intersect({span(1, 2, 0)}, {span(2, 3, 1)}).empty());
}

TEST(IntervalCsg, DifferenceBeginsWhereTheSubtrahendIsLeft) {
    // A = [1, 10], B = [0, 4] u [6, 7]: A - B = [4, 6] u [7, 10].
    const IntervalList out = subtract({span(1, 10, 0)}, {span(0, 4, 1), span(6, 7, 1)});
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].begin, 4.0);
    EXPECT_EQ(out[0].beginSurface.leaf, 1);
    EXPECT_FALSE(out[0].beginSurface.leafEnters);  // B's exit is where A - B begins
    EXPECT_EQ(out[0].end, 6.0);
    EXPECT_TRUE(out[0].endSurface.leafEnters);
    EXPECT_EQ(out[1].begin, 7.0);
    EXPECT_EQ(out[1].end, 10.0);
    EXPECT_EQ(out[1].endSurface.leaf, 0);

    const auto change = firstChange(out);
    ASSERT_TRUE(change.has_value());
    EXPECT_EQ(change->t, 4.0);
    EXPECT_TRUE(change->resultEnters);
    EXPECT_TRUE(change->flipNormal());
}

TEST(IntervalCsg, RayStartingInsideSeesTheFirstExit) {
    const IntervalList inside{span(-kInf, 3, 0)};
    const auto change = firstChange(inside);
    ASSERT_TRUE(change.has_value());
    EXPECT_EQ(change->t, 3.0);
    EXPECT_FALSE(change->resultEnters);
    EXPECT_FALSE(change->flipNormal());  // the leaf is left where the result is left
    EXPECT_FALSE(firstChange({span(-kInf, kInf, 0)}).has_value());
    EXPECT_FALSE(firstChange({}).has_value());
}

TEST(IntervalCsg, LeafIntervalsFollowParity) {
    // Crossings out of order; an even count: the ray starts outside.
    std::vector<Crossing> crossings{{5.0, false, 1}, {2.0, true, 0}, {7.0, true, 2}, {9.0, false, 3}};
    IntervalList list = leafIntervals(4, crossings, 1e-9);
    ASSERT_EQ(list.size(), 2u);
    EXPECT_EQ(list[0].begin, 2.0);
    EXPECT_EQ(list[0].end, 5.0);
    EXPECT_EQ(list[1].begin, 7.0);
    EXPECT_EQ(list[1].end, 9.0);
    EXPECT_EQ(list[0].beginSurface.leaf, 4);
    EXPECT_EQ(list[0].beginSurface.crossing, 0);
    EXPECT_TRUE(list[0].beginSurface.leafEnters);
    EXPECT_EQ(list[1].endSurface.crossing, 3);

    // An odd count: inside from the start.
    std::vector<Crossing> odd{{4.0, false, 0}, {6.0, true, 1}, {8.0, false, 2}};
    list = leafIntervals(0, odd, 1e-9);
    ASSERT_EQ(list.size(), 2u);
    EXPECT_EQ(list[0].begin, -kInf);
    EXPECT_EQ(list[0].beginSurface.leaf, -1);
    EXPECT_EQ(list[0].end, 4.0);

    // A graze (two crossings at one point) changes nothing; three at one point toggle once.
    std::vector<Crossing> graze{{2.0, true, 0}, {3.0, true, 1}, {3.0 + 1e-13, false, 2}, {5.0, false, 3}};
    list = leafIntervals(0, graze, 1e-9);
    ASSERT_EQ(list.size(), 1u);
    EXPECT_EQ(list[0].begin, 2.0);
    EXPECT_EQ(list[0].end, 5.0);
    std::vector<Crossing> triple{{3.0, true, 0}, {3.0, false, 1}, {3.0, true, 2}, {5.0, false, 3}};
    list = leafIntervals(0, triple, 1e-9);
    ASSERT_EQ(list.size(), 1u);
    EXPECT_EQ(list[0].begin, 3.0);
    EXPECT_EQ(list[0].beginSurface.crossing, 0);  // the first that faces the right way
    std::vector<Crossing> none;
    EXPECT_TRUE(leafIntervals(0, none, 1e-9).empty());
}

TEST(IntervalCsg, EmptyNodesFollowTheSharedSemantics) {
    strata::scene::Tree tree;
    const int a = tree.addLeaf({});
    const int b = tree.addLeaf({});
    const int emptyUnion = tree.addNode(NodeKind::Union, {});
    std::vector<IntervalList> lists{{span(1, 5, 0)}, {span(2, 3, 1)}};
    CsgProgram::Workspace workspace;

    tree.root = tree.addNode(NodeKind::Union, {a, emptyUnion});
    EXPECT_EQ(CsgProgram(tree).evaluate(lists, workspace).size(), 1u);
    tree.root = tree.addNode(NodeKind::Intersection, {a, emptyUnion});
    EXPECT_TRUE(CsgProgram(tree).evaluate(lists, workspace).empty());
    tree.root = tree.addNode(NodeKind::Difference, {emptyUnion, a});
    EXPECT_TRUE(CsgProgram(tree).evaluate(lists, workspace).empty());
    tree.root = tree.addNode(NodeKind::Difference, {a, emptyUnion});
    EXPECT_EQ(CsgProgram(tree).evaluate(lists, workspace).size(), 1u);
    tree.root = tree.addNode(NodeKind::Intersection, {});
    EXPECT_TRUE(CsgProgram(tree).evaluate(lists, workspace).empty());
    tree.root = -1;
    EXPECT_TRUE(CsgProgram(tree).evaluate(lists, workspace).empty());

    // A background leaf is not in the CSG: a - %b is a.
    tree.leaves[1].display = strata::scene::Display::Background;
    tree.root = tree.addNode(NodeKind::Difference, {a, b});
    const CsgProgram program(tree);
    EXPECT_EQ(program.leaves(), std::vector<int>{0});
    const IntervalList& out = program.evaluate(lists, workspace);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].begin, 1.0);
    EXPECT_EQ(out[0].end, 5.0);
}

TEST(IntervalCsg, MalformedTreesThrow) {
    strata::scene::Tree tree;
    const int a = tree.addLeaf({});
    tree.root = tree.addNode(NodeKind::Union, {a, 42});
    EXPECT_THROW(CsgProgram{tree}, strata::Error);
    const int loop = tree.addNode(NodeKind::Union, {a});
    tree.nodes[static_cast<std::size_t>(loop)].children.push_back(loop);
    tree.root = loop;
    EXPECT_THROW(CsgProgram{tree}, strata::Error);
    tree.root = 99;
    EXPECT_THROW(CsgProgram{tree}, strata::Error);
    tree.nodes[static_cast<std::size_t>(a)].leaf = 7;
    tree.root = a;
    EXPECT_THROW(CsgProgram{tree}, strata::Error);
}

namespace {

// Brute force: membership of the tree at one point, recursively, from each
// leaf's membership there.
bool member(const strata::scene::Tree& tree, int node, const std::vector<bool>& inLeaf) {
    const auto& n = tree.nodes[static_cast<std::size_t>(node)];
    switch (n.kind) {
        case NodeKind::Leaf:
            return inLeaf[static_cast<std::size_t>(n.leaf)];
        case NodeKind::Union:
            return std::any_of(n.children.begin(), n.children.end(), [&](int c) { return member(tree, c, inLeaf); });
        case NodeKind::Intersection:
            return !n.children.empty() &&
                   std::all_of(n.children.begin(), n.children.end(), [&](int c) { return member(tree, c, inLeaf); });
        case NodeKind::Difference:
            if (n.children.empty() || !member(tree, n.children[0], inLeaf)) return false;
            return std::none_of(n.children.begin() + 1, n.children.end(),
                                [&](int c) { return member(tree, c, inLeaf); });
    }
    return false;
}

int randomTree(strata::scene::Tree& tree, std::mt19937& rng, int depth, int leafNodes) {
    std::uniform_int_distribution<int> pick(0, 9);
    if (depth == 0 || pick(rng) < 3) {
        return std::uniform_int_distribution<int>(0, leafNodes - 1)(rng);  // leaf nodes come first
    }
    const NodeKind kinds[] = {NodeKind::Union, NodeKind::Intersection, NodeKind::Difference};
    const NodeKind kind = kinds[std::uniform_int_distribution<int>(0, 2)(rng)];
    const int arity = std::uniform_int_distribution<int>(0, 10)(rng) == 0 ? 0 : std::uniform_int_distribution<int>(1, 4)(rng);
    std::vector<int> children;
    for (int k = 0; k < arity; ++k) children.push_back(randomTree(tree, rng, depth - 1, leafNodes));
    return tree.addNode(kind, children);
}

struct Boundary {
    int leaf;
    bool enters;
};

// Runs `trials` random trees over random leaf lists whose boundary times come
// from `times` (distinct across all leaves when `distinct`).
void bruteForce(int trials, bool distinct, unsigned seed) {
    std::mt19937 rng(seed);
    const int leafCount = 6;
    for (int trial = 0; trial < trials; ++trial) {
        strata::scene::Tree tree;
        for (int i = 0; i < leafCount; ++i) tree.addLeaf({});
        tree.root = randomTree(tree, rng, 5, leafCount);

        // Leaf lists: sorted distinct boundary times, alternately begin/end.
        std::vector<IntervalList> lists(leafCount);
        std::map<double, Boundary> owner;  // only meaningful when distinct
        std::set<double> used;
        std::uniform_real_distribution<double> real(0.0, 100.0);
        std::uniform_int_distribution<int> small(1, 12);
        for (int leaf = 0; leaf < leafCount; ++leaf) {
            const int count = std::uniform_int_distribution<int>(0, 6)(rng);
            std::set<double> times;
            while (static_cast<int>(times.size()) < count) {
                const double t = distinct ? real(rng) : static_cast<double>(small(rng));
                if (distinct && used.count(t)) continue;
                times.insert(t);
                used.insert(t);
            }
            bool inside = std::uniform_int_distribution<int>(0, 3)(rng) == 0;  // inside from the start
            double begin = -kInf;
            int crossing = leaf * 100;
            Surface beginSurface{};
            for (double t : times) {
                const Surface here{leaf, crossing++, !inside};
                if (inside) {
                    lists[leaf].push_back({begin, t, beginSurface, here});
                } else {
                    begin = t;
                    beginSurface = here;
                }
                owner[t] = {leaf, !inside};
                inside = !inside;
            }
            if (inside) lists[leaf].push_back({begin, kInf, beginSurface, Surface{}});
        }

        CsgProgram::Workspace workspace;
        const IntervalList& result = CsgProgram(tree).evaluate(lists, workspace);
        ASSERT_TRUE(canonical(result)) << "trial " << trial;

        // Sample between every pair of boundaries.
        std::vector<double> events(used.begin(), used.end());
        std::vector<double> samples;
        samples.push_back(events.empty() ? 0.0 : events.front() - 1.0);
        for (std::size_t k = 0; k + 1 < events.size(); ++k) samples.push_back((events[k] + events[k + 1]) / 2);
        if (!events.empty()) samples.push_back(events.back() + 1.0);
        std::vector<bool> expected;
        for (double s : samples) {
            std::vector<bool> inLeaf(leafCount);
            for (int leaf = 0; leaf < leafCount; ++leaf) inLeaf[leaf] = contains(lists[leaf], s);
            expected.push_back(tree.root >= 0 && member(tree, tree.root, inLeaf));
            ASSERT_EQ(contains(result, s), expected.back()) << "trial " << trial << " at t = " << s;
        }

        // The first change: the first boundary where membership differs on its two sides.
        const auto change = firstChange(result);
        std::size_t k = 0;
        while (k + 1 < expected.size() && expected[k] == expected[k + 1]) ++k;
        if (k + 1 >= expected.size()) {
            EXPECT_FALSE(change.has_value()) << "trial " << trial;
            continue;
        }
        ASSERT_TRUE(change.has_value()) << "trial " << trial;
        EXPECT_EQ(change->t, events[k]) << "trial " << trial;
        EXPECT_EQ(change->resultEnters, expected[k + 1]) << "trial " << trial;
        if (distinct) {
            const Boundary& b = owner.at(events[k]);
            EXPECT_EQ(change->surface.leaf, b.leaf) << "trial " << trial;
            EXPECT_EQ(change->surface.leafEnters, b.enters) << "trial " << trial;
        }
    }
}

}  // namespace

TEST(IntervalCsg, RandomTreesAgreeWithPointSampling) { bruteForce(3000, true, 1); }

TEST(IntervalCsg, RandomTreesWithCoincidentBoundariesAgreeWithPointSampling) { bruteForce(3000, false, 2); }
