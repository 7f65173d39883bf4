// The default view frames what OpenSCAD frames: the positive terms of the
// CSG, not what is subtracted (OpenSCAD 2021.01's CSGProducts bounding box).

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "strata/camera/ViewBounds.h"
#include "strata/model/Model.h"

using namespace strata;

namespace {

// A cube of side `size` with its lower corner at `at`.
int cube(scene::Tree& tree, glm::dvec3 at, double size, scene::Display display = scene::Display::Normal) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{glm::dvec3(size), false};
    leaf.transform = glm::translate(glm::dmat4(1.0), at);
    leaf.display = display;
    return tree.addLeaf(std::move(leaf));
}

void expectBox(const mesh::Bounds& b, glm::dvec3 min, glm::dvec3 max) {
    EXPECT_EQ(b.min, min);
    EXPECT_EQ(b.max, max);
}

}  // namespace

TEST(ViewBounds, DifferenceFramesItsFirstChildOnly) {
    scene::Tree tree;
    const int a = cube(tree, {0, 0, 0}, 2);
    const int b = cube(tree, {1, 1, -5}, 10);  // reaches far beyond A
    tree.root = tree.addNode(scene::NodeKind::Difference, {a, b});
    expectBox(camera::viewBounds(tree, model::buildModel(tree)), {0, 0, 0}, {2, 2, 2});
}

TEST(ViewBounds, TheSubtrahendOfASubtrahendIsPositiveAgain) {
    scene::Tree tree;
    const int a = cube(tree, {0, 0, 0}, 2);
    const int b = cube(tree, {10, 0, 0}, 2);
    const int c = cube(tree, {0, 0, 20}, 1);
    const int inner = tree.addNode(scene::NodeKind::Difference, {b, c});
    tree.root = tree.addNode(scene::NodeKind::Difference, {a, inner});
    // A - (B - C) = A*!B + A*C: A and C frame the view, B does not.
    expectBox(camera::viewBounds(tree, model::buildModel(tree)), {0, 0, 0}, {2, 2, 21});
}

TEST(ViewBounds, UnionsIntersectionsAndBackgroundPartsAllCount) {
    scene::Tree tree;
    const int a = cube(tree, {0, 0, 0}, 1);
    const int b = cube(tree, {5, 0, 0}, 1);
    const int c = cube(tree, {0, 7, 0}, 1);
    const int i = tree.addNode(scene::NodeKind::Intersection, {a, b});  // OpenSCAD extends, not intersects
    tree.root = tree.addNode(scene::NodeKind::Union, {i, c});
    tree.background.push_back(cube(tree, {0, 0, -3}, 1, scene::Display::Background));
    expectBox(camera::viewBounds(tree, model::buildModel(tree)), {0, 0, -3}, {6, 8, 1});
}

TEST(ViewBounds, NothingToFrameIsEmpty) {
    scene::Tree tree;
    tree.root = tree.addNode(scene::NodeKind::Union, {});
    EXPECT_TRUE(camera::viewBounds(tree, model::buildModel(tree)).empty());
}
