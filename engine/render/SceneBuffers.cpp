#include "SceneBuffers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "Convexity.h"
#include "ShaderInterface.h"
#include "strata/core/Error.h"
#include "strata/geometry/LastCorners.h"

namespace strata::render {

void setSurfaceView(gpu::Program& program, const ViewSetup& view) {
    program.setUniform(shader::kSurfaceViewProjection, view.viewProjection);
    program.setUniform(shader::kSurfaceEye, view.eye);
    program.setUniform(shader::kSurfaceForward, view.forward);
}

void SceneBuffers::upload(const scene::Tree& tree, const geometry::Model& model) {
    if (model.leafMeshes.size() != tree.leaves.size()) {
        throw Error("renderer: the model has " + std::to_string(model.leafMeshes.size()) +
                    " leaf meshes for a tree of " + std::to_string(tree.leaves.size()) + " leaves");
    }
    // Each triangle ends on a vertex of its own (lastCornerLayout), which
    // carries its face normal: the provoking vertex of a flat varying.
    std::vector<float> positions;         // by 3, the layouts' vertices
    std::vector<float> normals;           // by 3, per layout vertex; a triangle's on its last corner
    vertices_.clear();
    firstVertex_.assign(1, 0);
    std::vector<std::uint32_t> indices;      // #F by 3, absolute, as the mesh has them
    std::vector<std::uint32_t> flatIndices;  // the same triangles in the layout
    leaves_.assign(model.leafMeshes.size(), {});
    leafColors_.clear();
    bounds_ = {};
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        const geometry::Mesh& mesh = model.leafMeshes[i];
        const geometry::LastCornerLayout layout = geometry::lastCornerLayout(mesh);
        const std::size_t firstVertex = positions.size() / 3;
        if (firstVertex + layout.source.size() > 0xffffffffu) throw Error("renderer: more than 2^32 vertices");
        LeafRange& range = leaves_[i];
        range.firstIndex = indices.size();
        for (const glm::dvec3& p : mesh.positions) {
            vertices_.emplace_back(p);
            range.bounds.extend(p);
        }
        firstVertex_.push_back(vertices_.size());
        for (std::uint32_t v : layout.source) {
            const glm::dvec3& p = mesh.positions[v];
            for (double c : {p.x, p.y, p.z}) positions.push_back(static_cast<float>(c));
        }
        normals.resize(positions.size(), 0.0f);
        for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
            const auto& t = mesh.triangles[f];
            // The layout starts with the mesh's vertices, so both index the same positions.
            for (std::uint32_t v : t) indices.push_back(static_cast<std::uint32_t>(firstVertex) + v);
            for (std::uint32_t v : layout.triangles[f]) {
                flatIndices.push_back(static_cast<std::uint32_t>(firstVertex) + v);
            }
            const glm::dvec3& a = mesh.positions[t[0]];
            glm::dvec3 n = glm::cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);
            const double length = glm::length(n);
            n = length > 0.0 ? n / length : glm::dvec3(0.0);
            const std::size_t last = 3 * (firstVertex + layout.triangles[f][2]);
            normals[last] = static_cast<float>(n.x);
            normals[last + 1] = static_cast<float>(n.y);
            normals[last + 2] = static_cast<float>(n.z);
        }
        range.indexCount = indices.size() - range.firstIndex;
        range.convex = range.indexCount > 0 && isConvexLeaf(tree.leaves[i].primitive, mesh);
        range.solidShells = range.convex || everyShellHasVolume(mesh);
        if (range.indexCount > 0) bounds_.extend(range.bounds);
        const auto& c = tree.leaves[i].color;
        leafColors_.push_back(c ? glm::vec4(*c) : glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    }
    planes_.assign(leaves_.size(), {});  // hashed on demand: hashPlanes
    sharing_.clear();
    positions_ = gpu::Buffer::fromSpan("scene positions", std::span<const float>(positions), 0);
    indices_ = gpu::Buffer::fromSpan("scene indices", std::span<const std::uint32_t>(indices), 0);
    flatIndices_ = gpu::Buffer::fromSpan("scene indices, flat normals", std::span<const std::uint32_t>(flatIndices), 0);
    faceNormals_ = gpu::Buffer::fromSpan("scene face normals", std::span<const float>(normals), 0);
    vertexArray_ = gpu::VertexArray("scene");
    vertexArray_.setVertexBuffer(0, positions_, 0, 3 * sizeof(float));
    vertexArray_.setAttribute(0, 0, 3, GL_FLOAT, 0);
    vertexArray_.setElementBuffer(indices_);
    flatVertexArray_ = gpu::VertexArray("scene with face normals");
    flatVertexArray_.setVertexBuffer(0, positions_, 0, 3 * sizeof(float));
    flatVertexArray_.setAttribute(0, 0, 3, GL_FLOAT, 0);
    flatVertexArray_.setVertexBuffer(1, faceNormals_, 0, 3 * sizeof(float));
    flatVertexArray_.setAttribute(1, 1, 3, GL_FLOAT, 0);
    flatVertexArray_.setElementBuffer(flatIndices_);
}

void SceneBuffers::drawLeaf(int leaf) const {
    const LeafRange& range = leaves_[static_cast<std::size_t>(leaf)];
    if (range.indexCount == 0) return;
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.indexCount), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(range.firstIndex * sizeof(std::uint32_t)));
}

void SceneBuffers::hashPlanes(const geometry::Model& model, const std::vector<int>& leaves) {
    // Unit normal and offset rounded to a billionth (of 1, and of the scene's size).
    const double unit = std::max(bounds_.empty() ? 1.0 : bounds_.diagonal(), 1e-300) * 1e-9;
    for (int leaf : leaves) {
        const auto i = static_cast<std::size_t>(leaf);
        std::vector<std::uint64_t>& keys = planes_[i];
        if (!leaves_[i].convex || !keys.empty()) continue;
        const geometry::Mesh& mesh = model.leafMeshes[i];
        for (const auto& t : mesh.triangles) {
            const glm::dvec3& a = mesh.positions[t[0]];
            const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);
            const double length = glm::length(n);
            if (!(length > 0.0)) continue;
            const glm::dvec3 u = n / length;
            std::uint64_t key = 1469598103934665603ull;
            for (double c : {u.x * 1e9, u.y * 1e9, u.z * 1e9, glm::dot(u, a) / unit}) {
                key = (key ^ static_cast<std::uint64_t>(std::llround(c))) * 1099511628211ull;
            }
            keys.push_back(key);
        }
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    }
}

bool SceneBuffers::shareAPlane(const std::vector<int>& leaves) const {
    const auto found = sharing_.find(leaves);
    if (found != sharing_.end()) return found->second;
    std::vector<std::uint64_t> all;
    for (int leaf : leaves) {
        const std::vector<std::uint64_t>& keys = planes_[static_cast<std::size_t>(leaf)];
        all.insert(all.end(), keys.begin(), keys.end());  // each leaf's keys are unique
    }
    std::sort(all.begin(), all.end());
    const bool shared = std::adjacent_find(all.begin(), all.end()) != all.end();
    sharing_.emplace(leaves, shared);
    return shared;
}

std::span<const glm::vec3> SceneBuffers::leafVertices(int leaf) const {
    const auto i = static_cast<std::size_t>(leaf);
    return std::span<const glm::vec3>(vertices_).subspan(firstVertex_[i], firstVertex_[i + 1] - firstVertex_[i]);
}

std::size_t SceneBuffers::bytes() const {
    return positions_.size() + indices_.size() + flatIndices_.size() + faceNormals_.size();
}

}  // namespace strata::render
