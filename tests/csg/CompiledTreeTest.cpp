// The tree compiler against a direct, recursive reading of the CSG tree.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "strata/csg/CompiledTree.h"
#include "strata/csg/ConvexGroups.h"

using namespace strata;
using scene::NodeKind;
using scene::Tree;

namespace {

int leaf(Tree& tree, scene::Display display = scene::Display::Normal) {
    scene::Leaf l;
    l.primitive = scene::Cube{};
    l.display = display;
    return tree.addLeaf(l);
}

// Membership of `node` when leaf i is inside iff inside[i], straight from the
// tree's meaning: union = any, intersection = all, difference = first and none
// of the rest, no children = empty, background and empty leaves = empty.
bool direct(const Tree& tree, int node, const std::vector<bool>& inside, const std::vector<bool>& empty) {
    const scene::Node& n = tree.nodes[static_cast<std::size_t>(node)];
    switch (n.kind) {
        case NodeKind::Leaf: {
            const auto i = static_cast<std::size_t>(n.leaf);
            if (tree.leaves[i].display == scene::Display::Background) return false;
            if (i < empty.size() && empty[i]) return false;
            return inside[i];
        }
        case NodeKind::Union: {
            bool any = false;
            for (int c : n.children) any = any || direct(tree, c, inside, empty);
            return any;
        }
        case NodeKind::Intersection: {
            if (n.children.empty()) return false;
            bool all = true;
            for (int c : n.children) all = all && direct(tree, c, inside, empty);
            return all;
        }
        case NodeKind::Difference: {
            if (n.children.empty()) return false;
            bool result = direct(tree, n.children[0], inside, empty);
            for (std::size_t i = 1; i < n.children.size(); ++i) {
                result = result && !direct(tree, n.children[i], inside, empty);
            }
            return result;
        }
    }
    return false;
}

std::vector<bool> operandStates(const csg::CompiledTree& compiled, const std::vector<bool>& leafInside) {
    std::vector<bool> states;
    for (int l : compiled.operandLeaf) states.push_back(leafInside[static_cast<std::size_t>(l)]);
    return states;
}

// A random tree: kinds, arities 0..4, some background and empty leaves.
int randomNode(Tree& tree, std::mt19937& rng, int depth) {
    std::uniform_int_distribution<int> pick(0, 9);
    if (depth == 0 || pick(rng) < 3) {
        return leaf(tree, pick(rng) == 0 ? scene::Display::Background : scene::Display::Normal);
    }
    const NodeKind kinds[] = {NodeKind::Union, NodeKind::Intersection, NodeKind::Difference};
    const NodeKind kind = kinds[std::uniform_int_distribution<int>(0, 2)(rng)];
    const int arity = std::uniform_int_distribution<int>(0, 4)(rng);
    std::vector<int> children;
    for (int i = 0; i < arity; ++i) children.push_back(randomNode(tree, rng, depth - 1));
    return tree.addNode(kind, children);
}

// Calls f(compiled, rng) for each of 300 seeded random trees (randomNode,
// `depth` levels) that compiles to code rather than a constant.
template <class F>
void forRandomTrees(unsigned seed, int depth, F f) {
    std::mt19937 rng(seed);
    for (int t = 0; t < 300; ++t) {
        Tree tree;
        tree.root = randomNode(tree, rng, depth);
        const csg::CompiledTree compiled = csg::compileTree(tree);
        if (compiled.kind == csg::CompiledTree::Kind::Code) f(compiled, rng);
    }
}

// Makes each leaf after the first, with chance 1 in `oneIn`, a copy of a
// random lower one (IdenticalLeaves.h's sameLeaf, returned); a copy is the
// same solid, so a background leaf's copies are background too.
std::vector<int> randomCopies(Tree& tree, std::mt19937& rng, unsigned oneIn) {
    const std::size_t n = tree.leaves.size();
    std::vector<int> same(n);
    for (std::size_t i = 0; i < n; ++i) {
        same[i] = i > 0 && rng() % oneIn == 0 ? same[rng() % i] : static_cast<int>(i);
        tree.leaves[i].display = tree.leaves[static_cast<std::size_t>(same[i])].display;
    }
    return same;
}

// Random leaf states, every copy inside exactly where its original is.
std::vector<bool> randomStates(const std::vector<int>& same, std::mt19937& rng) {
    std::vector<bool> inside(same.size());
    for (std::size_t i = 0; i < inside.size(); ++i) inside[i] = (rng() & 1u) != 0;
    for (std::size_t i = 0; i < inside.size(); ++i) inside[i] = inside[static_cast<std::size_t>(same[i])];
    return inside;
}

}  // namespace

TEST(CompiledTree, DifferenceBecomesIntersectionWithComplements) {
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree);
    tree.root = tree.addNode(NodeKind::Difference, {a, b, c});
    const csg::CompiledTree compiled = csg::compileTree(tree);
    ASSERT_EQ(compiled.kind, csg::CompiledTree::Kind::Code);
    EXPECT_EQ(csg::disassemble(compiled), "PUSH 0\nAND !1\nAND !2\n");
    EXPECT_EQ(compiled.stackDepth, 1);
    EXPECT_EQ(compiled.operandLeaf, (std::vector<int>{0, 1, 2}));
}

TEST(CompiledTree, ComplementsReachTheLeavesByDeMorgan) {
    // a - (b ∪ c) = a ∩ ¬b ∩ ¬c, flattened into one AND;
    // a - (b ∩ c) = a ∩ (¬b ∪ ¬c).
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree);
    const int u = tree.addNode(NodeKind::Union, {b, c});
    tree.root = tree.addNode(NodeKind::Difference, {a, u});
    EXPECT_EQ(csg::disassemble(csg::compileTree(tree)), "PUSH 0\nAND !1\nAND !2\n");

    Tree tree2;
    const int a2 = leaf(tree2), b2 = leaf(tree2), c2 = leaf(tree2);
    const int i2 = tree2.addNode(NodeKind::Intersection, {b2, c2});
    tree2.root = tree2.addNode(NodeKind::Difference, {a2, i2});
    // The subexpression (¬b ∪ ¬c) goes first, the literal a is fused after it.
    EXPECT_EQ(csg::disassemble(csg::compileTree(tree2)), "PUSH !1\nOR !2\nAND 0\n");
}

TEST(CompiledTree, EmptySetsFold) {
    {   // union() is empty
        Tree tree;
        tree.root = tree.addNode(NodeKind::Union, {});
        EXPECT_EQ(csg::compileTree(tree).kind, csg::CompiledTree::Kind::Empty);
    }
    {   // intersection with an empty child is empty
        Tree tree;
        const int a = leaf(tree);
        tree.root = tree.addNode(NodeKind::Intersection, {a, tree.addNode(NodeKind::Union, {})});
        EXPECT_EQ(csg::compileTree(tree).kind, csg::CompiledTree::Kind::Empty);
    }
    {   // difference with an empty first child is empty
        Tree tree;
        const int e = tree.addNode(NodeKind::Union, {});
        tree.root = tree.addNode(NodeKind::Difference, {e, leaf(tree)});
        EXPECT_EQ(csg::compileTree(tree).kind, csg::CompiledTree::Kind::Empty);
    }
    {   // subtracting the empty set, or an empty intersection, leaves the minuend
        Tree tree;
        const int a = leaf(tree), b = leaf(tree);
        const int emptyInter = tree.addNode(NodeKind::Intersection, {b, tree.addNode(NodeKind::Union, {})});
        tree.root = tree.addNode(NodeKind::Difference, {a, emptyInter, tree.addNode(NodeKind::Intersection, {})});
        const auto compiled = csg::compileTree(tree);
        EXPECT_EQ(csg::disassemble(compiled), "PUSH 0\n");
        EXPECT_EQ(compiled.operandLeaf, (std::vector<int>{0}));  // b is not an operand
    }
    {   // an empty leaf (no triangles) and a background leaf drop out of a union
        Tree tree;
        const int a = leaf(tree), b = leaf(tree), c = leaf(tree, scene::Display::Background);
        tree.root = tree.addNode(NodeKind::Union, {a, b, c});
        const auto compiled = csg::compileTree(tree, {true, false, false});
        EXPECT_EQ(csg::disassemble(compiled), "PUSH 0\n");
        EXPECT_EQ(compiled.operandLeaf, (std::vector<int>{1}));
    }
    {   // no root at all
        Tree tree;
        EXPECT_EQ(csg::compileTree(tree).kind, csg::CompiledTree::Kind::Empty);
    }
}

TEST(CompiledTree, NestedNodesOfOneKindFlatten) {
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree), d = leaf(tree);
    const int inner = tree.addNode(NodeKind::Union, {b, tree.addNode(NodeKind::Union, {c, d})});
    tree.root = tree.addNode(NodeKind::Union, {a, inner});
    EXPECT_EQ(csg::disassemble(csg::compileTree(tree)), "PUSH 0\nOR 1\nOR 2\nOR 3\n");
}

TEST(CompiledTree, MatchesTheTreeOnRandomTreesAndStates) {
    std::mt19937 rng(20240611);
    int codes = 0;
    for (int t = 0; t < 400; ++t) {
        Tree tree;
        tree.root = randomNode(tree, rng, 5);
        std::vector<bool> empty(tree.leaves.size());
        for (std::size_t i = 0; i < empty.size(); ++i) empty[i] = (rng() % 13) == 0;
        const csg::CompiledTree compiled = csg::compileTree(tree, empty);
        if (compiled.kind == csg::CompiledTree::Kind::Code) ++codes;
        for (int s = 0; s < 64; ++s) {
            std::vector<bool> inside(tree.leaves.size());
            for (std::size_t i = 0; i < inside.size(); ++i) inside[i] = (rng() & 1u) != 0;
            ASSERT_EQ(csg::runCompiledTree(compiled, operandStates(compiled, inside)),
                      direct(tree, tree.root, inside, empty))
                << "tree " << t << ", state " << s << "\n" << csg::disassemble(compiled);
        }
        // Every operand is a leaf that the tree uses, in ascending order.
        for (std::size_t k = 1; k < compiled.operandLeaf.size(); ++k) {
            EXPECT_LT(compiled.operandLeaf[k - 1], compiled.operandLeaf[k]);
        }
        // Sethi–Ullman: at most floor(log2(literals)) + 1 stack entries.
        int literals = 0;
        for (std::uint32_t instruction : compiled.code) literals += (instruction & csg::kOpFromStack) ? 0 : 1;
        if (literals > 0) {
            EXPECT_LE(compiled.stackDepth, static_cast<int>(std::floor(std::log2(literals))) + 1);
        }
    }
    EXPECT_GT(codes, 100);  // the random trees are not all folded away
}

TEST(CompiledTree, MatchesTheTreeWhereLeavesRepeat) {
    // Random trees whose leaves are random copies of lower ones (sameLeaf):
    // the copies share an operand, and an AND's (OR's) literal becomes a
    // constant inside its other children. The tree's own meaning, with every
    // copy inside exactly where its original is, is the reference.
    std::mt19937 rng(20261123);
    int codes = 0, shorter = 0;
    for (int t = 0; t < 400; ++t) {
        Tree tree;
        tree.root = randomNode(tree, rng, 5);
        const std::vector<int> same = randomCopies(tree, rng, 2);
        const csg::CompiledTree compiled = csg::compileTree(tree, {}, same);
        if (compiled.kind != csg::CompiledTree::Kind::Code) continue;
        ++codes;
        const csg::CompiledTree unshared = csg::compileTree(tree);
        const bool unsharedIsCode = unshared.kind == csg::CompiledTree::Kind::Code;
        if (unsharedIsCode && compiled.code.size() < unshared.code.size()) ++shorter;
        for (int s = 0; s < 64; ++s) {
            const std::vector<bool> inside = randomStates(same, rng);
            ASSERT_EQ(csg::runCompiledTree(compiled, operandStates(compiled, inside)),
                      direct(tree, tree.root, inside, {}))
                << "tree " << t << ", state " << s << "\n" << csg::disassemble(compiled);
        }
        for (int leaf : compiled.operandLeaf) EXPECT_EQ(same[static_cast<std::size_t>(leaf)], leaf);
    }
    EXPECT_GT(codes, 100);
    EXPECT_GT(shorter, 50);  // the literals that ancestors hold do fold away
}

TEST(CompiledTree, AChainIntersectedWithOneSolidAtEveryLevelKeepsOneIntersection) {
    // strata-bench's deep scene: c, then union, difference, ... with the same
    // sphere s intersected every 8th step. Sharing s, only the outermost
    // intersection with it is left; every other s literal folds away.
    Tree tree;
    int node = leaf(tree);
    std::vector<int> same{0};
    int sphere = -1;
    for (int i = 1; i < 64; ++i) {
        const int l = leaf(tree);
        NodeKind kind = i % 4 == 2 ? NodeKind::Difference : NodeKind::Union;
        if (i % 8 == 0) {
            kind = NodeKind::Intersection;
            if (sphere < 0) sphere = tree.nodes[static_cast<std::size_t>(l)].leaf;
            same.push_back(sphere);
        } else {
            same.push_back(tree.nodes[static_cast<std::size_t>(l)].leaf);
        }
        node = tree.addNode(kind, {node, l});
    }
    tree.root = node;
    const csg::CompiledTree compiled = csg::compileTree(tree, {}, same);
    int sphereLiterals = 0;
    for (std::uint32_t instruction : compiled.code) {
        if (instruction & csg::kOpFromStack) continue;
        const int operand = static_cast<int>(instruction >> csg::kOperandShift);
        sphereLiterals += compiled.operandLeaf[static_cast<std::size_t>(operand)] == sphere ? 1 : 0;
    }
    EXPECT_EQ(sphereLiterals, 1);
    EXPECT_EQ(compiled.operandCount(), 64 - 6);  // the 7 spheres are one operand
    std::mt19937 rng(5);
    for (int s = 0; s < 200; ++s) {
        const std::vector<bool> inside = randomStates(same, rng);
        ASSERT_EQ(csg::runCompiledTree(compiled, operandStates(compiled, inside)), direct(tree, tree.root, inside, {}));
    }
}

TEST(CompiledTree, BalancedTreeStackGrowsWithLogOfLeaves) {
    // A complete binary tree of 1024 leaves alternating union and intersection
    // by level cannot flatten: its stack need is exactly its height, 10.
    Tree tree;
    std::vector<int> level;
    for (int i = 0; i < 1024; ++i) level.push_back(leaf(tree));
    bool unionLevel = true;
    while (level.size() > 1) {
        std::vector<int> next;
        for (std::size_t i = 0; i < level.size(); i += 2) {
            next.push_back(tree.addNode(unionLevel ? NodeKind::Union : NodeKind::Intersection,
                                        {level[i], level[i + 1]}));
        }
        level = next;
        unionLevel = !unionLevel;
    }
    tree.root = level.front();
    const auto compiled = csg::compileTree(tree);
    EXPECT_EQ(compiled.stackDepth, 10);
    EXPECT_EQ(compiled.operandCount(), 1024);
    // Spot-check the meaning on a few states against the tree itself.
    std::mt19937 rng(7);
    for (int s = 0; s < 50; ++s) {
        std::vector<bool> inside(1024);
        for (std::size_t i = 0; i < inside.size(); ++i) inside[i] = (rng() % 4) != 0;
        EXPECT_EQ(csg::runCompiledTree(compiled, operandStates(compiled, inside)),
                  direct(tree, tree.root, inside, {}));
    }
}

TEST(CompiledTree, VeryDeepChainsCompileWithoutRecursionAndOneStackEntry) {
    // union(a0, intersection(a1, union(a2, ...))) 200000 levels deep.
    Tree tree;
    int node = leaf(tree);
    for (int i = 0; i < 200000; ++i) {
        node = tree.addNode(i % 2 ? NodeKind::Union : NodeKind::Intersection, {leaf(tree), node});
    }
    tree.root = node;
    const auto compiled = csg::compileTree(tree);
    EXPECT_EQ(compiled.stackDepth, 1);
    EXPECT_EQ(compiled.code.size(), 200001u);
}

TEST(CompiledTree, DeepChainsOfOneKindFlattenInLinearMemory) {
    // difference(difference(... difference(a, b1) ..., b199999), b200000):
    // one AND of 200001 literals. Flattening level by level would hold a
    // list per level, 2e10 entries in all.
    Tree tree;
    int node = leaf(tree);
    for (int i = 0; i < 200000; ++i) node = tree.addNode(NodeKind::Difference, {node, leaf(tree)});
    tree.root = node;
    const auto compiled = csg::compileTree(tree);
    EXPECT_EQ(compiled.stackDepth, 1);
    EXPECT_EQ(compiled.code.size(), 200001u);
    EXPECT_EQ(compiled.operandLeaf.size(), 200001u);
}

TEST(CompiledTree, SharedSubtreesAreEvaluatedWherePlaced) {
    // The same node used twice, once subtracted: (a ∪ b) - (a ∩ b) = a xor b.
    Tree tree;
    const int a = leaf(tree), b = leaf(tree);
    const int u = tree.addNode(NodeKind::Union, {a, b});
    const int i = tree.addNode(NodeKind::Intersection, {a, b});
    tree.root = tree.addNode(NodeKind::Difference, {u, i});
    const auto compiled = csg::compileTree(tree);
    EXPECT_EQ(compiled.operandCount(), 2);
    for (int s = 0; s < 4; ++s) {
        const bool ia = s & 1, ib = s & 2;
        EXPECT_EQ(csg::runCompiledTree(compiled, {ia, ib}), ia != ib) << s;
    }
}

TEST(CompiledTree, CyclesAndBadIndicesAreErrors) {
    Tree tree;
    const int a = leaf(tree);
    const int u = tree.addNode(NodeKind::Union, {a});
    tree.nodes[static_cast<std::size_t>(u)].children.push_back(u);
    tree.root = u;
    EXPECT_THROW(csg::compileTree(tree), Error);

    Tree bad;
    bad.root = bad.addNode(NodeKind::Union, {42});
    EXPECT_THROW(csg::compileTree(bad), Error);
}

TEST(CompiledTree, SpecializingToPresentOperandsKeepsTheMeaning) {
    // Where an operand has no surface it is outside: the specialised code
    // must agree with the full one on every state with absent operands outside.
    int folded = 0, constants = 0;
    forRandomTrees(99, 5, [&](const csg::CompiledTree& compiled, std::mt19937& rng) {
        for (int m = 0; m < 8; ++m) {
            std::vector<char> present(static_cast<std::size_t>(compiled.operandCount()));
            for (char& p : present) p = (rng() % 3) != 0;
            bool constant = false;
            const std::vector<std::uint32_t> code = csg::specializeCode(compiled, present, &constant);
            EXPECT_LE(code.size(), compiled.code.size());
            folded += code.size() < compiled.code.size() ? 1 : 0;
            constants += code.empty() ? 1 : 0;
            for (int s = 0; s < 16; ++s) {
                std::vector<bool> inside(present.size());
                for (std::size_t k = 0; k < inside.size(); ++k) inside[k] = present[k] && (rng() & 1u);
                const bool want = csg::runCompiledTree(compiled, inside);
                const bool got = code.empty() ? constant : csg::runCode(code, inside);
                ASSERT_EQ(got, want) << csg::disassemble(compiled);
            }
        }
    });
    EXPECT_GT(folded, 100);
    EXPECT_GT(constants, 10);
}

TEST(CompiledTree, SpecializingACheeseLeavesOnlyTheNearbyHoles) {
    // cube - s1 - s2 - s3 where only s2 is present: cube AND !s2.
    Tree tree;
    std::vector<int> children;
    for (int i = 0; i < 4; ++i) children.push_back(leaf(tree));
    tree.root = tree.addNode(NodeKind::Difference, children);
    const csg::CompiledTree compiled = csg::compileTree(tree);
    csg::CompiledTree view = compiled;
    view.code = csg::specializeCode(compiled, {1, 0, 1, 0});
    EXPECT_EQ(csg::disassemble(view), "PUSH 0\nAND !2\n");
    bool constant = true;
    EXPECT_TRUE(csg::specializeCode(compiled, {0, 1, 1, 1}, &constant).empty());  // no cube: empty
    EXPECT_FALSE(constant);
}

namespace {

// The evaluator's incremental update (shaders/csg/evaluate.frag, array form):
// one literal changes, counts climb while node values change.
struct CountingState {
    const csg::CountingTree& tree;
    std::vector<std::uint32_t> trueChildren;
    std::vector<bool> inside;

    CountingState(const csg::CountingTree& t, std::size_t operands) : tree(t), inside(operands, false) {
        for (const csg::CountingTree::Node& n : tree.nodes) trueChildren.push_back(n.trueWhenOutside);
    }
    bool value(std::uint32_t node) const {
        const csg::CountingTree::Node& n = tree.nodes[node];
        return n.isAnd ? trueChildren[node] == n.children : trueChildren[node] != 0;
    }
    void set(std::uint32_t operand, bool now) {
        if (inside[operand] == now) return;
        inside[operand] = now;
        for (const csg::CountingTree::Literal& l : tree.literals) {
            if (l.operand != operand) continue;
            bool rising = now != l.negated;
            for (std::uint32_t node = l.parent; node != csg::CountingTree::kNoParent;) {
                const bool before = value(node);
                trueChildren[node] += rising ? 1u : std::uint32_t(-1);
                const bool after = value(node);
                if (after == before) break;
                rising = after;
                node = tree.nodes[node].parent;
            }
        }
    }
};

}  // namespace

TEST(CompiledTree, CountingTreesFollowTheCodeOneChangeAtATime) {
    int checked = 0;
    forRandomTrees(7, 6, [&](const csg::CompiledTree& compiled, std::mt19937& rng) {
        const csg::CountingTree counting = csg::countingTree(compiled.code);

        // Shape: the root first, every parent before its children, each
        // literal and non-root node counted once as a child.
        ASSERT_FALSE(counting.nodes.empty());
        EXPECT_EQ(counting.nodes[0].parent, csg::CountingTree::kNoParent);
        std::uint32_t children = 0;
        for (std::size_t i = 0; i < counting.nodes.size(); ++i) {
            children += counting.nodes[i].children;
            if (i > 0) {
                EXPECT_LT(counting.nodes[i].parent, i);
            }
        }
        EXPECT_EQ(children, counting.literals.size() + counting.nodes.size() - 1);

        const auto operands = static_cast<std::size_t>(compiled.operandCount());
        CountingState state(counting, operands);
        EXPECT_EQ(state.value(0), csg::runCompiledTree(compiled, state.inside));
        for (int step = 0; step < 40; ++step) {
            state.set(static_cast<std::uint32_t>(rng() % operands), (rng() & 1u) != 0);
            ASSERT_EQ(state.value(0), csg::runCompiledTree(compiled, state.inside)) << csg::disassemble(compiled);
            ASSERT_EQ(csg::runCountingTree(counting, state.inside), state.value(0));
            ++checked;
        }
    });
    EXPECT_GT(checked, 4000);
}

TEST(CompiledTree, ACheeseIsOneCountingNode) {
    // cube - s1 - s2 - s3 = cube AND !s1 AND !s2 AND !s3: one AND of four,
    // three of them true while everything is outside.
    Tree tree;
    std::vector<int> children;
    for (int i = 0; i < 4; ++i) children.push_back(leaf(tree));
    tree.root = tree.addNode(NodeKind::Difference, children);
    const csg::CountingTree counting = csg::countingTree(csg::compileTree(tree).code);
    ASSERT_EQ(counting.nodes.size(), 1u);
    EXPECT_TRUE(counting.nodes[0].isAnd);
    EXPECT_EQ(counting.nodes[0].children, 4u);
    EXPECT_EQ(counting.nodes[0].trueWhenOutside, 3u);
    EXPECT_EQ(counting.literals.size(), 4u);
}

// Operand states where a group operand is inside where all its members are.
std::vector<bool> groupedStates(const csg::CompiledTree& compiled, const std::vector<bool>& leafInside) {
    std::vector<bool> states = operandStates(compiled, leafInside);
    for (std::size_t k = 0; k < compiled.operandGroups.size(); ++k) {
        for (int member : compiled.operandGroups[k]) {
            states[k] = states[k] && leafInside[static_cast<std::size_t>(member)];
        }
    }
    return states;
}

TEST(ConvexGroups, KeepTheTreesMeaningOnRandomTrees) {
    // Random trees (some leaves repeated), random operands marked groupable,
    // groups of at most 2 to 5: the grouped tree, a group inside where
    // all its members are, against the tree's own meaning.
    std::mt19937 rng(20261124);
    int grouped = 0;
    for (int t = 0; t < 1500; ++t) {
        Tree tree;
        tree.root = randomNode(tree, rng, 5);
        const std::vector<int> same = randomCopies(tree, rng, 5);
        const csg::CompiledTree compiled = csg::compileTree(tree, {}, same);
        std::vector<char> groupable(compiled.operandLeaf.size());
        for (char& g : groupable) g = rng() % 4 != 0 ? 1 : 0;
        const std::size_t most = 2 + rng() % 4;
        const csg::CompiledTree groups = csg::groupConvexProducts(compiled, groupable, most);
        ASSERT_EQ(groups.kind, compiled.kind);
        if (groups.kind != csg::CompiledTree::Kind::Code) continue;
        if (groups.operandCount() < compiled.operandCount()) ++grouped;
        for (int s = 0; s < 64; ++s) {
            const std::vector<bool> inside = randomStates(same, rng);
            ASSERT_EQ(csg::runCompiledTree(groups, groupedStates(groups, inside)),
                      direct(tree, tree.root, inside, {}))
                << "tree " << t << ", state " << s << "\n" << csg::disassemble(compiled) << "grouped:\n"
                << csg::disassemble(groups);
        }
        // Every operand of the first tree is in exactly one operand of the
        // second; operands stay ascending; a group is groupable leaves only.
        std::vector<int> seen;
        for (std::size_t k = 0; k < groups.operandLeaf.size(); ++k) {
            if (k > 0) {
                EXPECT_LT(groups.operandLeaf[k - 1], groups.operandLeaf[k]);
            }
            const bool isGroup = k < groups.operandGroups.size() && !groups.operandGroups[k].empty();
            if (!isGroup) {
                seen.push_back(groups.operandLeaf[k]);
                continue;
            }
            const std::vector<int>& members = groups.operandGroups[k];
            EXPECT_EQ(members.front(), groups.operandLeaf[k]);
            EXPECT_GE(members.size(), 2u);
            EXPECT_LE(members.size(), most);
            for (int member : members) {
                seen.push_back(member);
                const auto at = std::find(compiled.operandLeaf.begin(), compiled.operandLeaf.end(), member);
                ASSERT_NE(at, compiled.operandLeaf.end());
                EXPECT_TRUE(groupable[static_cast<std::size_t>(at - compiled.operandLeaf.begin())]);
            }
        }
        std::sort(seen.begin(), seen.end());
        EXPECT_EQ(seen, compiled.operandLeaf);
    }
    EXPECT_GT(grouped, 50);  // some of the random trees have groups
}

TEST(ConvexGroups, AnIntersectionOfSolidsIsOneOperandInRunsOfTheMost) {
    Tree tree;
    std::vector<int> children;
    for (int i = 0; i < 10; ++i) children.push_back(leaf(tree));
    tree.root = tree.addNode(NodeKind::Intersection, children);
    const csg::CompiledTree compiled = csg::compileTree(tree);
    const std::vector<char> all(10, 1);
    const csg::CompiledTree one = csg::groupConvexProducts(compiled, all, 255);
    ASSERT_EQ(one.operandCount(), 1);
    EXPECT_EQ(one.operandGroups[0], (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
    EXPECT_EQ(csg::disassemble(one), "PUSH 0\n");
    const csg::CompiledTree runs = csg::groupConvexProducts(compiled, all, 4);
    ASSERT_EQ(runs.operandCount(), 3);
    std::vector<std::size_t> sizes;
    for (const auto& g : runs.operandGroups) sizes.push_back(g.size());
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<std::size_t>{2, 4, 4}));
    // Not groupable: nothing changes.
    const csg::CompiledTree none = csg::groupConvexProducts(compiled, std::vector<char>(10, 0), 255);
    EXPECT_EQ(none.code, compiled.code);
    EXPECT_TRUE(none.operandGroups.empty());
}

TEST(ConvexGroups, AnIntersectionOfFewerThanTheLeastStaysApart) {
    // (A n B n C) - (D n E): the first intersection has three literals to
    // join, the subtracted one two (!D | !E once compiled).
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree), d = leaf(tree), e = leaf(tree);
    tree.root = tree.addNode(NodeKind::Difference, {tree.addNode(NodeKind::Intersection, {a, b, c}),
                                                    tree.addNode(NodeKind::Intersection, {d, e})});
    const csg::CompiledTree compiled = csg::compileTree(tree);
    const std::vector<char> all(5, 1);
    EXPECT_EQ(csg::groupConvexProducts(compiled, all, 255, 2).operandCount(), 2);
    const csg::CompiledTree three = csg::groupConvexProducts(compiled, all, 255, 3);
    ASSERT_EQ(three.operandCount(), 3);  // the group of A, B and C; D; E
    EXPECT_EQ(three.operandGroups[0], (std::vector<int>{0, 1, 2}));
    const csg::CompiledTree four = csg::groupConvexProducts(compiled, all, 255, 4);
    EXPECT_EQ(four.code, compiled.code);
    EXPECT_TRUE(four.operandGroups.empty());
    // Each form means what the tree does, on every membership of the five.
    for (std::uint32_t inside = 0; inside < 32; ++inside) {
        const bool want = (inside & 7u) == 7u && (inside & 24u) != 24u;
        for (const csg::CompiledTree* form : {&compiled, &three}) {
            std::vector<bool> in(static_cast<std::size_t>(form->operandCount()));
            for (std::size_t k = 0; k < in.size(); ++k) {
                bool every = true;
                for (int member : form->leavesOf(k)) every = every && ((inside >> member) & 1u);
                in[k] = every;
            }
            EXPECT_EQ(csg::runCode(form->code, in), want) << inside;
        }
    }
}

TEST(ConvexGroups, SubtractedAndRepeatedSolidsStayTheirOwn) {
    // (A - B - C) u (D n E) u (D n F): B and C are subtracted, D is in two
    // intersections, and E and F would be groups of one.
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree), d = leaf(tree), e = leaf(tree), f = leaf(tree);
    tree.root = tree.addNode(NodeKind::Union, {tree.addNode(NodeKind::Difference, {a, b, c}),
                                               tree.addNode(NodeKind::Intersection, {d, e}),
                                               tree.addNode(NodeKind::Intersection, {d, f})});
    const csg::CompiledTree compiled = csg::compileTree(tree);
    const csg::CompiledTree same = csg::groupConvexProducts(compiled, std::vector<char>(6, 1), 255);
    EXPECT_EQ(same.code, compiled.code);
    EXPECT_EQ(same.operandLeaf, compiled.operandLeaf);
}

TEST(ConvexGroups, ASubtractedIntersectionIsOneNegatedOperand) {
    // A - (B n C) is A n (!B u !C): the OR's negated literals are !(B n C).
    Tree tree;
    const int a = leaf(tree), b = leaf(tree), c = leaf(tree);
    tree.root = tree.addNode(NodeKind::Difference, {a, tree.addNode(NodeKind::Intersection, {b, c})});
    const csg::CompiledTree grouped =
        csg::groupConvexProducts(csg::compileTree(tree), std::vector<char>(3, 1), 255);
    ASSERT_EQ(grouped.operandLeaf, (std::vector<int>{0, 1}));
    EXPECT_EQ(grouped.operandGroups[1], (std::vector<int>{1, 2}));
    for (int state = 0; state < 8; ++state) {
        const std::vector<bool> inside{(state & 1) != 0, (state & 2) != 0, (state & 4) != 0};
        EXPECT_EQ(csg::runCompiledTree(grouped, groupedStates(grouped, inside)), direct(tree, tree.root, inside, {}));
    }
}

// Operand states where an intersection group is inside where all its
// members are, and a union group where any is.
std::vector<bool> unitedStates(const csg::CompiledTree& compiled, const std::vector<bool>& leafInside) {
    std::vector<bool> states = operandStates(compiled, leafInside);
    for (std::size_t k = 0; k < compiled.operandGroups.size(); ++k) {
        if (compiled.operandGroups[k].empty()) continue;
        const bool unite = compiled.isUnionGroup(k);
        bool state = !unite;
        for (int member : compiled.operandGroups[k]) {
            const bool in = leafInside[static_cast<std::size_t>(member)];
            state = unite ? state || in : state && in;
        }
        states[k] = state;
    }
    return states;
}

TEST(UnionGroups, KeepTheTreesMeaningOnRandomTrees) {
    // Random trees, intersections grouped first, then random operands
    // joined in unions of at most 2 to 5: the tree's meaning is kept, every
    // union group is groupable leaves joined by one OR, and intersection
    // groups are left as they were.
    std::mt19937 rng(20261126);
    int united = 0;
    for (int t = 0; t < 1500; ++t) {
        Tree tree;
        tree.root = randomNode(tree, rng, 5);
        const std::vector<int> same = randomCopies(tree, rng, 5);
        const csg::CompiledTree compiled = csg::compileTree(tree, {}, same);
        std::vector<char> convex(compiled.operandLeaf.size());
        for (char& g : convex) g = rng() % 2 != 0 ? 1 : 0;
        const csg::CompiledTree groups = csg::groupConvexProducts(compiled, convex, 3);
        std::vector<char> groupable(groups.operandLeaf.size());
        for (char& g : groupable) g = rng() % 4 != 0 ? 1 : 0;
        const std::size_t most = 2 + rng() % 4;
        const csg::CompiledTree unions = csg::groupUnionOperands(groups, groupable, most);
        ASSERT_EQ(unions.kind, groups.kind);
        if (unions.kind != csg::CompiledTree::Kind::Code) continue;
        if (unions.operandCount() < groups.operandCount()) ++united;
        for (int s = 0; s < 64; ++s) {
            const std::vector<bool> inside = randomStates(same, rng);
            ASSERT_EQ(csg::runCompiledTree(unions, unitedStates(unions, inside)), direct(tree, tree.root, inside, {}))
                << "tree " << t << ", state " << s << "\n" << csg::disassemble(groups) << "united:\n"
                << csg::disassemble(unions);
        }
        for (std::size_t k = 0; k < unions.operandLeaf.size(); ++k) {
            const std::span<const int> members = unions.leavesOf(k);
            const auto at = std::find(groups.operandLeaf.begin(), groups.operandLeaf.end(), members.front());
            ASSERT_NE(at, groups.operandLeaf.end());
            const auto before = static_cast<std::size_t>(at - groups.operandLeaf.begin());
            if (!unions.isUnionGroup(k)) {
                // Unchanged: the same leaf, or the same intersection group.
                const std::span<const int> was = groups.leavesOf(before);
                EXPECT_TRUE(std::equal(members.begin(), members.end(), was.begin(), was.end()));
                continue;
            }
            EXPECT_GE(members.size(), 2u);
            EXPECT_LE(members.size(), most);
            for (int member : members) {
                const auto m = std::find(groups.operandLeaf.begin(), groups.operandLeaf.end(), member);
                ASSERT_NE(m, groups.operandLeaf.end());
                const auto j = static_cast<std::size_t>(m - groups.operandLeaf.begin());
                EXPECT_TRUE(groupable[j]);
                EXPECT_EQ(groups.leavesOf(j).size(), 1u) << "an intersection group joined a union";
            }
        }
    }
    EXPECT_GT(united, 50);
}

TEST(UnionGroups, AUnionOfSolidsIsOneOperandInRunsOfTheMost) {
    Tree tree;
    std::vector<int> children;
    for (int i = 0; i < 10; ++i) children.push_back(leaf(tree));
    tree.root = tree.addNode(NodeKind::Union, children);
    const csg::CompiledTree compiled = csg::compileTree(tree);
    const std::vector<char> all(10, 1);
    const csg::CompiledTree one = csg::groupUnionOperands(compiled, all, 65535);
    ASSERT_EQ(one.operandCount(), 1);
    EXPECT_TRUE(one.isUnionGroup(0));
    EXPECT_EQ(one.operandGroups[0], (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
    EXPECT_EQ(csg::disassemble(one), "PUSH 0\n");
    const csg::CompiledTree runs = csg::groupUnionOperands(compiled, all, 4);
    ASSERT_EQ(runs.operandCount(), 3);
    std::vector<std::size_t> sizes;
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_TRUE(runs.isUnionGroup(k));
        sizes.push_back(runs.operandGroups[k].size());
    }
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<std::size_t>{2, 4, 4}));
    // An intersection's literals and a subtracted union's never join a union.
    Tree other;
    const int a = leaf(other), b = leaf(other), c = leaf(other), d = leaf(other);
    other.root = other.addNode(NodeKind::Difference, {other.addNode(NodeKind::Intersection, {a, b}),
                                                      other.addNode(NodeKind::Union, {c, d})});
    const csg::CompiledTree product = csg::compileTree(other);
    const csg::CompiledTree kept = csg::groupUnionOperands(product, std::vector<char>(4, 1), 65535);
    EXPECT_EQ(kept.code, product.code);
    EXPECT_TRUE(kept.unionGroups.empty());
}
