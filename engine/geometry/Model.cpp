#include "strata/geometry/Model.h"

#include <cmath>
#include <string>
#include <type_traits>
#include <variant>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "strata/core/Error.h"
#include "strata/geometry/Extrude.h"
#include "strata/geometry/Flat.h"
#include "strata/geometry/Hull.h"
#include "strata/geometry/MeshCheck.h"
#include "strata/geometry/MeshImport.h"
#include "strata/geometry/Primitives.h"
#include "strata/geometry/Surface.h"

namespace strata::geometry {
namespace {

Mesh objectMesh(const scene::Primitive& p) {
    return std::visit(
        [](const auto& v) -> Mesh {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, scene::Import>) return importMesh(v.path);
            else if constexpr (std::is_same_v<T, scene::LinearExtrude>) return linearExtrude(v, evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::RotateExtrude>) return rotateExtrude(v, evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::FlatSlab>) return flatSlab(evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::Hull>) return tessellate(v);
            else return tessellate(v);
        },
        p);
}

// Marks the leaves reachable from `node`.
void markLeaves(const scene::Tree& tree, int node, std::vector<bool>& inCsg) {
    std::vector<int> stack{node};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= tree.nodes.size()) continue;
        const auto& nd = tree.nodes[static_cast<std::size_t>(n)];
        if (nd.kind == scene::NodeKind::Leaf) {
            if (nd.leaf >= 0 && static_cast<std::size_t>(nd.leaf) < inCsg.size()) inCsg[static_cast<std::size_t>(nd.leaf)] = true;
        } else {
            stack.insert(stack.end(), nd.children.begin(), nd.children.end());
        }
    }
}

}  // namespace

Mesh leafMesh(const scene::Leaf& leaf) { return transformed(objectMesh(leaf.primitive), leaf.transform); }

Model buildModel(const scene::Tree& tree) {
    Model model;
    model.leafMeshes.reserve(tree.leaves.size());
    // Bounds cover the leaves in the CSG result: reachable from the root and
    // not '%' background.
    std::vector<bool> inCsg(tree.leaves.size(), false);
    markLeaves(tree, tree.root, inCsg);

    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        const char* name = scene::primitiveName(leaf.primitive);
        Mesh mesh;
        try {
            mesh = leafMesh(leaf);
        } catch (const Error& e) {
            // Errors from the importer or tessellator name no input position;
            // a leaf read straight from a mesh file may already be named.
            if (leaf.where.file.empty() || std::string(e.what()).rfind(leaf.where.str() + ":", 0) == 0) throw;
            throw Error(leaf.where, e.what());
        }
        if (glm::determinant(glm::dmat3(leaf.transform)) == 0.0) {
            // A flattening transform (a scale of 0) leaves no volume: the leaf
            // takes part in the CSG as the empty solid.
            mesh = Mesh{};
        }
        for (const auto& p : mesh.positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                throw Error(leaf.where, std::string(name) + " has a non-finite coordinate after its transform");
            }
        }
        dropDegenerateTriangles(mesh);
        const MeshCheck check = checkMesh(mesh);
        if (!check.ok()) throw Error(leaf.where, std::string(name) + " is not a closed solid: " + check.describe());
        if (inCsg[i] && leaf.display != scene::Display::Background) model.bounds.extend(boundsOf(mesh));
        model.leafMeshes.push_back(std::move(mesh));
    }
    return model;
}

}  // namespace strata::geometry
