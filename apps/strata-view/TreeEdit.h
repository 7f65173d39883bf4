#pragma once
// The panel's per-node visibility and highlight, applied to a copy of the
// parsed tree as OpenSCAD's modifiers would be written in the source: a hidden
// node is dropped with its subtree (OpenSCAD's '*'), a highlighted one has
// every leaf under it marked Display::Highlight ('#'). The leaves vector is
// kept whole, so the model::Model built for the parsed tree still fits the
// edited one and no tessellation is redone.

#include <set>
#include <string>
#include <vector>

#include "strata/scene/Tree.h"

namespace strata::view {

struct TreeEdits {
    std::set<int> hidden;       // node indices into Tree::nodes
    std::set<int> highlighted;  // node indices into Tree::nodes

    bool empty() const { return hidden.empty() && highlighted.empty(); }
};

scene::Tree applyEdits(const scene::Tree& tree, const TreeEdits& edits);

// One node of the tree as the panel lists it: in depth-first order from the
// root, then the background ('%') roots.
struct TreeRow {
    int node = -1;
    int depth = 0;          // nesting level, 0 for the roots
    bool background = false;
    std::string label;      // "difference", "cube", "import a.stl", ...
};
std::vector<TreeRow> treeRows(const scene::Tree& tree);

// A script's NODE: a node number ("12") or "line:N", the outermost listed node
// written on line N. Throws strata::Error (without a position) when there is no such node.
int findNode(const scene::Tree& tree, const std::string& spec);

}  // namespace strata::view
