#include "strata/model/Model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/exact/Exact.h"
#include "strata/flat/Extrude.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/mesh/MeshImport.h"
#include "strata/mesh/Primitives.h"
#include "strata/mesh/Surface.h"
#include "strata/model/FlatEvaluation.h"
#include "strata/model/Hull.h"
#include "strata/model/Minkowski.h"

namespace strata::model {

using mesh::Bounds;
using mesh::Mesh;
using mesh::MeshCheck;
using mesh::boundsOf;
using mesh::checkMesh;
using mesh::dropDegenerateTriangles;
using flat::flatSlab;
using mesh::importMesh;
using flat::linearExtrude;
using flat::rotateExtrude;
using mesh::tessellate;
using mesh::transformed;

Mesh objectMesh(const scene::Primitive& p) {
    return std::visit(
        [](const auto& v) -> Mesh {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, scene::Import>) return importMesh(v.path);
            else if constexpr (std::is_same_v<T, scene::LinearExtrude>) return linearExtrude(v, evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::RotateExtrude>) return rotateExtrude(v, evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::FlatSlab>) return flatSlab(evaluateFlat(v.shape));
            else if constexpr (std::is_same_v<T, scene::Hull>) return tessellate(v);
            else if constexpr (std::is_same_v<T, scene::Exact>) {
                const Model solid = buildModel(*v.solid);
                return exact::exactResult(*v.solid, v.solid->root, solid.leafMeshes, objectMesh);
            }
            else if constexpr (std::is_same_v<T, scene::MinkowskiSum>) return minkowskiSum(v);
            else return tessellate(v);
        },
        p);
}

namespace {

// OpenSCAD's resize of the result that a resize() node's leaves make
// (PolySet::resize): each axis given a size is scaled to it, `auto` axes
// take the scale of the largest given one; then the resize's own placement.
void applyResize(const scene::Resize& resize, std::vector<Mesh>& meshes) {
    Bounds box;
    for (int l : resize.leaves) box.extend(boundsOf(meshes[static_cast<std::size_t>(l)]));
    if (box.empty()) return;
    const glm::dvec3 size = box.max - box.min;
    int largest = 0;
    for (int i = 1; i < 3; ++i)
        if (resize.newsize[i] > resize.newsize[largest]) largest = i;
    glm::dvec3 scale(1.0);
    for (int i = 0; i < 3; ++i) {
        if (resize.newsize[i] > 0) {
            // A flat result cannot be stretched across its plane: left as it is, as OpenSCAD does.
            if (size[i] == 0.0) return;
            scale[i] = resize.newsize[i] / size[i];
        }
    }
    const double autoscale = scale[largest];
    for (int i = 0; i < 3; ++i) {
        if (resize.autosize[i] && !(resize.newsize[i] > 0)) scale[i] = autoscale;
    }
    glm::dmat4 s(1.0);
    s[0][0] = scale.x;
    s[1][1] = scale.y;
    s[2][2] = scale.z;
    for (int l : resize.leaves) {
        Mesh& mesh = meshes[static_cast<std::size_t>(l)];
        mesh = transformed(transformed(mesh, s), resize.outer);
    }
}

}  // namespace

Mesh leafMesh(const scene::Leaf& leaf) { return transformed(objectMesh(leaf.primitive), leaf.transform); }

namespace {

// A leaf's mesh in world space, with errors named by the leaf's position.
Mesh meshOf(const scene::Leaf& leaf) {
    try {
        Mesh mesh = leafMesh(leaf);
        // A flattening transform (a scale of 0) leaves no volume: the leaf
        // takes part in the CSG as the empty solid.
        if (glm::determinant(glm::dmat3(leaf.transform)) == 0.0) mesh = Mesh{};
        return mesh;
    } catch (const Error& e) {
        // Errors from the importer or tessellator name no input position;
        // a leaf read straight from a mesh file may already be named.
        rethrowAt(leaf.where, e);
    }
}

// Solids a user wrote or imported (polyhedra, mesh files) get OpenSCAD's
// tolerance: a closed one wound inside out is turned outward.
bool userMesh(const scene::Primitive& p) {
    return std::holds_alternative<scene::Polyhedron>(p) || std::holds_alternative<scene::Import>(p);
}

// What was forgiven, one warning per kind at its first leaf, with a count.
class Forgiven {
public:
    void add(int kind, const scene::Leaf& leaf, const std::string& what) {
        Entry& e = entries_[kind];
        if (e.count++ == 0) e.message = leaf.where.str() + ": warning: " + what;
    }
    void writeTo(std::vector<Warning>& warnings) const {
        for (const Entry& e : entries_) {
            if (e.count == 0) continue;
            warnings.push_back(Warning{e.message + (e.count > 1 ? " (" + std::to_string(e.count) + " meshes in all)" : "")});
        }
    }
    static constexpr int kInsideOut = 0, kDegenerate = 1;

private:
    struct Entry {
        std::size_t count = 0;
        std::string message;
    };
    std::array<Entry, 2> entries_;
};

// The largest coordinate a solid may have in world space: far beyond any
// model (a kilometre in micrometres is 1e9), and small enough that the
// camera's distances and the GPU's single-precision depths stay finite.
constexpr double kMaxCoordinate = 1e12;

std::string shortNumber(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

// Cleans the leaf's mesh and checks it is a closed solid; notes what was forgiven.
void checkLeaf(const scene::Leaf& leaf, Mesh& mesh, Forgiven& forgiven) {
    const char* name = scene::primitiveName(leaf.primitive);
    for (const auto& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            throw Error(leaf.where, std::string(name) + " has a non-finite coordinate after its transform");
        }
        const double largest = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
        if (largest > kMaxCoordinate) {
            throw Error(leaf.where, std::string(name) + " reaches " + shortNumber(largest) +
                                        " after its transform; strata takes coordinates up to 1e12");
        }
    }
    const std::size_t before = mesh.triangles.size();
    dropDegenerateTriangles(mesh);
    MeshCheck check = checkMesh(mesh);
    if (userMesh(leaf.primitive) && mesh.triangles.size() < before) {
        forgiven.add(Forgiven::kDegenerate, leaf,
                     std::string(name) + " has degenerate triangles (no area); dropped");
    }
    if (userMesh(leaf.primitive) && check.inwardOriented && check.boundaryEdges == 0 && check.nonManifoldEdges == 0 &&
        check.misorientedEdges == 0) {
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
        forgiven.add(Forgiven::kInsideOut, leaf,
                     std::string(name) + " is inside out (every face wound the wrong way); turned outward");
        check = checkMesh(mesh);
    }
    if (!check.ok()) throw Error(leaf.where, std::string(name) + " is not a closed solid: " + check.describe());
}

}  // namespace

Model buildModel(const scene::Tree& tree) {
    Model model;
    model.leafMeshes.reserve(tree.leaves.size());
    // Bounds cover the leaves in the CSG result: reachable from the root and
    // not '%' background.
    std::vector<bool> inCsg(tree.leaves.size(), false);
    for (int l : tree.leavesUnder(tree.root)) inCsg[static_cast<std::size_t>(l)] = true;

    for (const scene::Leaf& leaf : tree.leaves) {
        reportProgress("meshing leaves", model.leafMeshes.size(), tree.leaves.size());
        model.leafMeshes.push_back(meshOf(leaf));
    }
    for (const scene::Resize& resize : tree.resizes) applyResize(resize, model.leafMeshes);
    Forgiven forgiven;
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        Mesh& mesh = model.leafMeshes[i];
        reportProgress("checking leaves", i, tree.leaves.size());
        checkLeaf(leaf, mesh, forgiven);
        if (inCsg[i] && leaf.display != scene::Display::Background) model.bounds.extend(boundsOf(mesh));
    }
    forgiven.writeTo(model.warnings);
    return model;
}

}  // namespace strata::model
