#include "strata/scene/Tree.h"

#include <algorithm>
#include <type_traits>
#include <utility>
#include <variant>

namespace strata::scene {

TransformStep::~TransformStep() {
    std::shared_ptr<const TransformStep> next = std::move(previous);
    // A step nothing else holds is emptied before it goes, so that its own
    // destructor has nothing left to follow.
    while (next && next.use_count() == 1) {
        std::shared_ptr<const TransformStep> after = std::move(next->previous);
        next = std::move(after);
    }
}

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

bool Tree::isFlat() const {
    const std::vector<int> result = leavesUnder(root);
    return !result.empty() && std::all_of(result.begin(), result.end(), [this](int l) {
        return std::holds_alternative<FlatSlab>(leaves[static_cast<std::size_t>(l)].primitive);
    });
}

std::vector<int> Tree::leavesUnder(int node) const {
    std::vector<int> found;
    std::vector<int> todo{node};
    while (!todo.empty()) {
        const int n = todo.back();
        todo.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= nodes.size()) continue;
        const Node& nd = nodes[static_cast<std::size_t>(n)];
        if (nd.kind != NodeKind::Leaf) {
            todo.insert(todo.end(), nd.children.rbegin(), nd.children.rend());
        } else if (nd.leaf >= 0 && static_cast<std::size_t>(nd.leaf) < leaves.size()) {
            found.push_back(nd.leaf);
        }
    }
    return found;
}

int FlatTree::add(FlatNode node) {
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

const char* primitiveName(const Primitive& primitive) {
    return std::visit(
        [](const auto& v) -> const char* {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, Cube>) return "cube";
            else if constexpr (std::is_same_v<T, Sphere>) return "sphere";
            else if constexpr (std::is_same_v<T, Cylinder>) return "cylinder";
            else if constexpr (std::is_same_v<T, Polyhedron>) return "polyhedron";
            else if constexpr (std::is_same_v<T, Import>) return "import";
            else if constexpr (std::is_same_v<T, LinearExtrude>) return "linear_extrude";
            else if constexpr (std::is_same_v<T, RotateExtrude>) return "rotate_extrude";
            else if constexpr (std::is_same_v<T, FlatSlab>) return "2D shape";
            else if constexpr (std::is_same_v<T, Hull>) return "hull";
            else if constexpr (std::is_same_v<T, Exact>) return "CSG result";
            else if constexpr (std::is_same_v<T, MinkowskiSum>) return "minkowski";
            else return "surface";
        },
        primitive);
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
