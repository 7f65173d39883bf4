#include "TreeEdit.h"

#include <charconv>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "strata/core/Error.h"

namespace strata::view {
namespace {

void markHighlight(scene::Tree& tree, int node) {
    // An explicit stack: parsed trees can nest deeper than the C++ stack allows.
    std::vector<int> stack{node};
    while (!stack.empty()) {
        const scene::Node& n = tree.nodes[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        if (n.kind == scene::NodeKind::Leaf) {
            scene::Leaf& leaf = tree.leaves[static_cast<std::size_t>(n.leaf)];
            if (leaf.display == scene::Display::Normal) leaf.display = scene::Display::Highlight;
        }
        stack.insert(stack.end(), n.children.begin(), n.children.end());
    }
}

std::string leafLabel(const scene::Leaf& leaf) {
    if (const auto* imported = std::get_if<scene::Import>(&leaf.primitive))
        return "import " + std::filesystem::path(imported->path).filename().string();
    if (const auto* surface = std::get_if<scene::Surface>(&leaf.primitive))
        return "surface " + std::filesystem::path(surface->path).filename().string();
    return scene::primitiveName(leaf.primitive);
}

}  // namespace

scene::Tree applyEdits(const scene::Tree& tree, const TreeEdits& edits) {
    scene::Tree edited = tree;
    if (edits.empty()) return edited;
    for (int node : edits.highlighted)
        if (node >= 0 && node < static_cast<int>(edited.nodes.size()) && !edits.hidden.contains(node))
            markHighlight(edited, node);
    for (scene::Node& n : edited.nodes) std::erase_if(n.children, [&](int c) { return edits.hidden.contains(c); });
    std::erase_if(edited.background, [&](int c) { return edits.hidden.contains(c); });
    if (edits.hidden.contains(edited.root)) edited.root = edited.addNode(scene::NodeKind::Union, {});
    return edited;
}

std::vector<TreeRow> treeRows(const scene::Tree& tree) {
    std::vector<TreeRow> rows;
    std::vector<std::pair<int, int>> stack;  // (node, depth), children pushed in reverse
    auto walk = [&](int root, bool background) {
        stack.emplace_back(root, 0);
        while (!stack.empty()) {
            const auto [node, depth] = stack.back();
            stack.pop_back();
            const scene::Node& n = tree.nodes[static_cast<std::size_t>(node)];
            TreeRow row{node, depth, background, {}};
            row.label = n.kind == scene::NodeKind::Leaf ? leafLabel(tree.leaves[static_cast<std::size_t>(n.leaf)])
                                                        : scene::kindName(n.kind);
            rows.push_back(std::move(row));
            for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.emplace_back(*c, depth + 1);
        }
    };
    if (tree.root >= 0) walk(tree.root, false);
    for (int b : tree.background) walk(b, true);
    return rows;
}

int findNode(const scene::Tree& tree, const std::string& spec) {
    // Scripts check NODE's form and range before they run (Script.cpp);
    // anything else that slips through is "no node", never an exception of
    // the standard library's.
    auto number = [](std::string_view digits) {
        long long value = -1;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (error != std::errc() || end != digits.data() + digits.size() || digits.empty()) return -1LL;
        return value;
    };
    if (spec.starts_with("line:")) {
        const long long line = number(std::string_view(spec).substr(5));
        for (const TreeRow& row : treeRows(tree))
            if (tree.nodes[static_cast<std::size_t>(row.node)].where.line == line) return row.node;
        throw Error("no node of the tree is written on line " + spec.substr(5));
    }
    const long long node = number(spec);
    if (tree.nodes.empty()) throw Error("no node " + spec + " (the tree is empty)");
    if (node < 0 || node >= static_cast<long long>(tree.nodes.size()))
        throw Error("no node " + spec + " (the tree has nodes 0 to " + std::to_string(tree.nodes.size() - 1) + ")");
    return static_cast<int>(node);
}

}  // namespace strata::view
