#include "CsgProduct.h"

#include <type_traits>
#include <variant>

namespace strata::bench {
namespace {

bool convexPrimitive(const scene::Primitive& primitive) {
    return std::visit(
        [](const auto& p) {
            using T = std::decay_t<decltype(p)>;
            return std::is_same_v<T, scene::Cube> || std::is_same_v<T, scene::Sphere> ||
                   std::is_same_v<T, scene::Cylinder> || std::is_same_v<T, scene::Hull>;
        },
        primitive);
}

ProductOperand operand(const scene::Tree& tree, const geometry::Model& model, int leafIndex, bool subtract,
                       geometry::Bounds& bounds) {
    ProductOperand out;
    out.subtract = subtract;
    out.convex = convexPrimitive(tree.leaves[static_cast<std::size_t>(leafIndex)].primitive);
    const geometry::Mesh& mesh = model.leafMeshes[static_cast<std::size_t>(leafIndex)];
    out.positions.reserve(mesh.triangles.size() * 9);
    for (const auto& triangle : mesh.triangles)
        for (std::uint32_t v : triangle) {
            const glm::dvec3& p = mesh.positions[v];
            bounds.extend(p);
            out.positions.insert(out.positions.end(),
                                 {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
        }
    return out;
}

// `index`, or the node it stands for: an operation with a single child (an
// OpenSCAD group() around one object, a mesh file's tree) is its child.
const scene::Node& throughSingles(const scene::Tree& tree, int index) {
    const scene::Node* node = &tree.nodes[static_cast<std::size_t>(index)];
    while (node->kind != scene::NodeKind::Leaf && node->children.size() == 1)
        node = &tree.nodes[static_cast<std::size_t>(node->children[0])];
    return *node;
}

}  // namespace

CsgProduct csgProduct(const scene::Tree& tree, const geometry::Model& model) {
    CsgProduct out;
    if (tree.root < 0) {
        out.notProduct = "empty scene";
        return out;
    }
    const scene::Node& root = throughSingles(tree, tree.root);
    if (root.kind == scene::NodeKind::Leaf) {
        out.operands.push_back(operand(tree, model, root.leaf, false, out.bounds));
        return out;
    }
    if (root.kind == scene::NodeKind::Union) {
        out.notProduct = "not one CSG product (unions)";
        return out;
    }
    for (std::size_t i = 0; i < root.children.size(); ++i) {
        const scene::Node& child = throughSingles(tree, root.children[i]);
        if (child.kind != scene::NodeKind::Leaf) {
            out = {};
            out.notProduct = "not one CSG product (nested operations)";
            return out;
        }
        const bool subtract = root.kind == scene::NodeKind::Difference && i > 0;
        out.operands.push_back(operand(tree, model, child.leaf, subtract, out.bounds));
    }
    return out;
}

}  // namespace strata::bench
