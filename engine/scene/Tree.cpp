#include "strata/scene/Tree.h"

#include <utility>

namespace strata::scene {

int Tree::addLeaf(Leaf leaf) {
    Node node;
    node.kind = NodeKind::Leaf;
    node.leaf = static_cast<int>(leaves.size());
    node.where = leaf.where;
    leaves.push_back(std::move(leaf));
    nodes.push_back(std::move(node));
    return static_cast<int>(nodes.size()) - 1;
}

int Tree::addNode(NodeKind kind, std::vector<int> children) {
    Node node;
    node.kind = kind;
    node.children = std::move(children);
    nodes.push_back(std::move(node));
    return static_cast<int>(nodes.size()) - 1;
}

Tree meshFileTree(const std::string& path) {
    Tree tree;
    tree.source = path;
    Leaf leaf;
    leaf.primitive = Import{path};
    leaf.where = SourceLocation{path, 0, 0};
    const int node = tree.addLeaf(std::move(leaf));
    tree.root = tree.addNode(NodeKind::Union, {node});
    return tree;
}

const char* kindName(NodeKind kind) {
    switch (kind) {
        case NodeKind::Leaf: return "leaf";
        case NodeKind::Union: return "union";
        case NodeKind::Intersection: return "intersection";
        case NodeKind::Difference: return "difference";
    }
    return "?";
}

}  // namespace strata::scene
