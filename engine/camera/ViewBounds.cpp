#include "strata/camera/ViewBounds.h"

#include <utility>
#include <vector>

namespace strata::camera {

mesh::Bounds viewBounds(const scene::Tree& tree, const model::Model& model) {
    mesh::Bounds bounds;
    // (node, positive): an explicit stack, so any tree depth costs no C++ stack.
    std::vector<std::pair<int, bool>> todo;
    if (tree.root >= 0) todo.emplace_back(tree.root, true);
    for (int b : tree.background) todo.emplace_back(b, true);
    std::vector<char> seen(tree.nodes.size() * 2, 0);
    while (!todo.empty()) {
        const auto [index, positive] = todo.back();
        todo.pop_back();
        if (index < 0 || static_cast<std::size_t>(index) >= tree.nodes.size()) continue;
        char& mark = seen[static_cast<std::size_t>(index) * 2 + (positive ? 1 : 0)];
        if (mark) continue;  // shared subtrees (and malformed cycles) are walked once
        mark = 1;
        const scene::Node& node = tree.nodes[static_cast<std::size_t>(index)];
        if (node.kind == scene::NodeKind::Leaf) {
            const auto leaf = static_cast<std::size_t>(node.leaf);
            if (positive && leaf < model.leafMeshes.size() && !model.leafMeshes[leaf].positions.empty())
                bounds.extend(mesh::boundsOf(model.leafMeshes[leaf]));
            continue;
        }
        for (std::size_t c = 0; c < node.children.size(); ++c) {
            // A difference's subtrahends flip the sign; everything else keeps it.
            const bool subtrahend = node.kind == scene::NodeKind::Difference && c > 0;
            todo.emplace_back(node.children[c], subtrahend ? !positive : positive);
        }
    }
    return bounds;
}

}  // namespace strata::camera
