// Which leaves the renderer peels once for several: the same triangles at
// the same places, with the same colour and display.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "strata/core/Error.h"
#include "strata/csg/CompiledTree.h"
#include "strata/csg/IdenticalLeaves.h"
#include "strata/model/Model.h"

using namespace strata;
using scene::NodeKind;

namespace {

scene::Leaf cube(glm::dvec3 at) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{{2.0, 2.0, 2.0}, false};
    leaf.transform = glm::translate(glm::dmat4(1.0), at);
    return leaf;
}

}  // namespace

TEST(IdenticalLeaves, SameSolidColourAndDisplayMapToTheLowest) {
    scene::Tree tree;
    std::vector<int> nodes;
    nodes.push_back(tree.addLeaf(cube({0, 0, 0})));                     // 0
    nodes.push_back(tree.addLeaf(cube({1, 0, 0})));                     // 1: elsewhere
    nodes.push_back(tree.addLeaf(cube({0, 0, 0})));                     // 2: as 0
    scene::Leaf red = cube({0, 0, 0});
    red.color = glm::dvec4(1, 0, 0, 1);
    nodes.push_back(tree.addLeaf(red));                                 // 3: another colour
    nodes.push_back(tree.addLeaf(red));                                 // 4: as 3
    scene::Leaf highlighted = cube({0, 0, 0});
    highlighted.display = scene::Display::Highlight;
    nodes.push_back(tree.addLeaf(highlighted));                         // 5: another display
    scene::Leaf sphere;
    sphere.primitive = scene::Sphere{};
    nodes.push_back(tree.addLeaf(sphere));                              // 6: another shape
    nodes.push_back(tree.addLeaf(cube({1, 0, 0})));                     // 7: as 1
    scene::Leaf tiny = cube({0, 0, 0});
    tiny.transform = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 + 1e-15));
    nodes.push_back(tree.addLeaf(tiny));                                // 8: one ulp away
    tree.root = tree.addNode(NodeKind::Union, nodes);
    const model::Model model = model::buildModel(tree);
    const std::vector<int> same = csg::identicalLeaves(tree, model);
    EXPECT_EQ(same, (std::vector<int>{0, 1, 0, 3, 3, 5, 6, 1, 8}));

    // compileTree: the copies' literals use their originals' operands.
    const csg::CompiledTree compiled = csg::compileTree(tree, {}, same);
    EXPECT_EQ(compiled.operandLeaf, (std::vector<int>{0, 1, 3, 5, 6, 8}));
    // Inside operand 0 only: leaves 0 and 2 both.
    EXPECT_TRUE(csg::runCompiledTree(compiled, {true, false, false, false, false, false}));
    EXPECT_FALSE(csg::runCompiledTree(compiled, {false, false, false, false, false, false}));
}

TEST(IdenticalLeaves, ACopyMinusItsOriginalIsEmpty) {
    // A ∩ ¬A, A's copy being A: the compiler folds it to the empty set.
    scene::Tree tree;
    const int a = tree.addLeaf(cube({0, 0, 0}));
    const int b = tree.addLeaf(cube({0, 0, 0}));
    tree.root = tree.addNode(NodeKind::Difference, {a, b});
    const model::Model model = model::buildModel(tree);
    EXPECT_EQ(csg::compileTree(tree, {}, csg::identicalLeaves(tree, model)).kind,
              csg::CompiledTree::Kind::Empty);
    EXPECT_EQ(csg::compileTree(tree).kind, csg::CompiledTree::Kind::Code);  // not shared: two operands
}

TEST(IdenticalLeaves, AnOutOfRangeMappingIsAnError) {
    scene::Tree tree;
    tree.root = tree.addNode(NodeKind::Union, {tree.addLeaf(cube({0, 0, 0}))});
    EXPECT_THROW(csg::compileTree(tree, {}, {3}), Error);
}
