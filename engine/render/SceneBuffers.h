#pragma once
// The scene on the GPU: every leaf's world-space triangles in one vertex and
// one index buffer, with per-leaf ranges, plus per-triangle face normals in a
// storage buffer. Shared by every pass that draws leaves.

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "strata/geometry/Model.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/VertexArray.h"
#include "strata/scene/Tree.h"

namespace strata::render {

struct LeafRange {
    std::size_t firstIndex = 0;     // into the index buffer
    std::size_t indexCount = 0;     // 3 per triangle; 0 for an empty leaf
    std::size_t firstTriangle = 0;  // into the face-normal buffer (and gl_PrimitiveID's origin)
    geometry::Bounds bounds;        // world space
    bool convex = false;
    bool solidShells = true;        // everyShellHasVolume (Convexity.h)
};

class SceneBuffers {
public:
    // Replaces the buffers with `model`'s meshes (tree.leaves[i] is
    // model.leafMeshes[i]). Leaf colours are tree.leaves[i].color.
    void upload(const scene::Tree& tree, const geometry::Model& model);

    // glDrawElements of leaf `leaf`'s triangles; the vertex array must be bound.
    // gl_PrimitiveID counts from 0 at the leaf's first triangle.
    void drawLeaf(int leaf) const;

    const gpu::VertexArray& vertexArray() const { return vertexArray_; }
    // std430 vec4 per triangle: xyz the outward unit face normal, w 0.
    const gpu::Buffer& faceNormals() const { return faceNormals_; }
    // Per leaf: its color() in rgba, a = -1 when it has none.
    const std::vector<glm::vec4>& leafColors() const { return leafColors_; }
    const std::vector<LeafRange>& leaves() const { return leaves_; }
    const LeafRange& leaf(int index) const { return leaves_[static_cast<std::size_t>(index)]; }
    // Of every leaf with triangles, background leaves included.
    const geometry::Bounds& bounds() const { return bounds_; }
    // Leaf `leaf`'s vertices (world space, as uploaded), for screen rectangles.
    std::span<const glm::vec3> leafVertices(int leaf) const;
    std::size_t bytes() const;

private:
    gpu::Buffer positions_;
    gpu::Buffer indices_;
    gpu::Buffer faceNormals_;
    gpu::VertexArray vertexArray_;
    std::vector<LeafRange> leaves_;
    std::vector<glm::vec4> leafColors_;
    std::vector<glm::vec3> vertices_;          // all leaves' vertices, as in positions_
    std::vector<std::size_t> firstVertex_;     // per leaf, and one past the last
    geometry::Bounds bounds_;
};

}  // namespace strata::render
