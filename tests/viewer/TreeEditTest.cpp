// The panel's tree edits (apps/strata-view/TreeEdit.h): hiding is OpenSCAD's
// '*', highlighting its '#', both on a copy that keeps every leaf.

#include <gtest/gtest.h>

#include "TreeEdit.h"

using namespace strata;

namespace {

scene::Leaf leafAt(int line) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{};
    leaf.where = SourceLocation{"t.csg", line, 2};
    return leaf;
}

// root(union, line 1) { difference(line 2) { cube(3), sphere-like cube(4) }, cube(6) }
struct Example {
    scene::Tree tree;
    int a, b, c, diff;
    Example() {
        a = tree.addLeaf(leafAt(3));
        b = tree.addLeaf(leafAt(4));
        diff = tree.addNode(scene::NodeKind::Difference, {a, b});
        tree.nodes[static_cast<std::size_t>(diff)].where = SourceLocation{"t.csg", 2, 1};
        c = tree.addLeaf(leafAt(6));
        tree.root = tree.addNode(scene::NodeKind::Union, {diff, c});
        tree.nodes[static_cast<std::size_t>(tree.root)].where = SourceLocation{"t.csg", 1, 1};
    }
};

}  // namespace

TEST(TreeEdit, HidingDropsTheSubtreeAndKeepsTheLeaves) {
    Example e;
    view::TreeEdits edits;
    edits.hidden.insert(e.a);  // like '*' on the difference's first child: the next one leads
    scene::Tree edited = view::applyEdits(e.tree, edits);
    EXPECT_EQ(edited.nodes[static_cast<std::size_t>(e.diff)].children, (std::vector<int>{e.b}));
    EXPECT_EQ(edited.leaves.size(), e.tree.leaves.size());

    edits.hidden = {e.tree.root};
    edited = view::applyEdits(e.tree, edits);
    const scene::Node& root = edited.nodes[static_cast<std::size_t>(edited.root)];
    EXPECT_EQ(root.kind, scene::NodeKind::Union);
    EXPECT_TRUE(root.children.empty());
}

TEST(TreeEdit, HighlightMarksEveryLeafBelow) {
    Example e;
    view::TreeEdits edits;
    edits.highlighted.insert(e.diff);
    const scene::Tree edited = view::applyEdits(e.tree, edits);
    EXPECT_EQ(edited.leaves[0].display, scene::Display::Highlight);
    EXPECT_EQ(edited.leaves[1].display, scene::Display::Highlight);
    EXPECT_EQ(edited.leaves[2].display, scene::Display::Normal);
    EXPECT_EQ(e.tree.leaves[0].display, scene::Display::Normal);  // the original is untouched
}

TEST(TreeEdit, RowsAreDepthFirstAndNodesAreFoundByNumberOrLine) {
    Example e;
    const auto rows = view::treeRows(e.tree);
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_EQ(rows[0].node, e.tree.root);
    EXPECT_EQ(rows[1].node, e.diff);
    EXPECT_EQ(rows[1].label, "difference");
    EXPECT_EQ(rows[2].depth, 2);
    EXPECT_EQ(rows[2].label, "cube");
    EXPECT_EQ(rows[4].node, e.c);

    EXPECT_EQ(view::findNode(e.tree, "line:2"), e.diff);
    EXPECT_EQ(view::findNode(e.tree, "line:6"), e.c);
    EXPECT_EQ(view::findNode(e.tree, std::to_string(e.b)), e.b);
    EXPECT_THROW(view::findNode(e.tree, "line:99"), Error);
    EXPECT_THROW(view::findNode(e.tree, "99"), Error);
    EXPECT_THROW(view::findNode(e.tree, "line:99999999999"), Error);
    EXPECT_THROW(view::findNode(e.tree, "99999999999999999999"), Error);
    EXPECT_THROW(view::findNode(e.tree, "x"), Error);
}
