#pragma once
// The scene on the GPU: every leaf's world-space triangles in one vertex
// buffer, with per-leaf ranges, and three vertex arrays over it, shared by
// every pass that draws leaves; one index buffer serves them all:
// - vertexArray(): positions (attribute 0), the triangles in
//   mesh::lastCornerLayout: each ends on a vertex of its own, copied
//   where needed. Corners keep the mesh's order, and copies their position,
//   so a triangle is set up and rasterized exactly as the mesh has it.
//   Attribute 1: the face plane of the triangle that ends on the vertex
//   (FacePlanes: its outward unit normal n and n . P for its points), where
//   a flat varying takes it (the provoking vertex): the passes need no
//   lookup by gl_PrimitiveID for the face normal or the depth along a
//   fragment's ray (surface.vert).
// - memberVertexArray(): positions, planes, and per instance its number (attribute
//   2, a float): drawn by a multi-draw whose draw m has base instance m, as
//   memberCommands makes it, each draw's vertices carry m (surface.vert's
//   GROUP_MEMBERS), so a group's members go in one call.
// - leafVertexArray(): positions, face planes, and per instance its number
//   (attribute 2) as memberVertexArray() has it: drawn by a multi-draw whose
//   draw of leaf i has base instance i (leafCommands), each fragment knows
//   its tree leaf (the plain path, PlainPass.h).
// A leaf's range indexes all alike. Every pass that draws them does so with
// shaders/csg/surface.vert as its vertex stage (setSurfaceView).

#include <cstddef>
#include <cstdint>
#include <array>
#include <map>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/VertexArray.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::render {

// glMultiDrawElementsIndirect's record.
struct DrawElementsIndirectCommand {
    GLuint count, instanceCount, firstIndex, baseVertex, baseInstance;
};

// The face planes of the scene's triangles, for the depth of a fragment
// along its ray (surface.vert). Triangles whose planes agree in double to a
// billionth (of a unit normal, and of the scene's size for the offset) are
// in one plane; where triangles of two leaves or more are (a face shared by
// two leaves, a subtrahend flush with a face), each gets the same float
// plane, bit for bit, so every one of them gives one depth at a pixel,
// where interpolating each triangle's vertex depths would round each its
// own way. A plane of one leaf alone gets the offset shader::kOwnPlane
// (interface.glsl): its fragments take the interpolated depth, which the
// leaf's triangles take from the vertices they share, so it stays
// continuous across the leaf's own edges.
class FacePlanes {
public:
    FacePlanes() = default;
    explicit FacePlanes(const mesh::Bounds& scene);
    // Notes the plane of leaf `leaf`'s triangle a b c (counter-clockwise from outside).
    void add(int leaf, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
    // The triangle's (n, n . a): the plane shared by every triangle added in
    // it, or its own normal with the offset kOwnPlane where one leaf alone has that plane;
    // zero for a degenerate triangle.
    glm::vec4 of(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const;
    // The plane of the triangle a b c as one number, equal for triangles in
    // one plane (and, rarely, for others: a hash); none for a degenerate one.
    std::optional<std::uint64_t> hashOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const;

private:
    using Key = std::array<long long, 4>;
    static std::uint64_t hashKey(const Key& k);
    struct KeyHash {
        std::size_t operator()(const Key& k) const { return static_cast<std::size_t>(hashKey(k)); }
    };
    struct Entry {
        glm::vec4 plane;
        int leaf;     // the first leaf seen with it
        bool shared;  // another leaf has it too
    };
    bool keyOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, Key& key, glm::vec4& plane) const;
    double unit_ = 1e-9;
    std::unordered_map<Key, Entry, KeyHash> planes_;
};

struct LeafRange {
    std::size_t firstIndex = 0;     // into the index buffer
    std::size_t indexCount = 0;     // 3 per triangle; 0 for an empty leaf
    mesh::Bounds bounds;        // world space
    bool convex = false;
    bool solidShells = true;        // everyShellHasVolume (Convexity.h)
};

class SceneBuffers {
public:
    // Replaces the scene with `model`'s meshes (tree.leaves[i] is
    // model.leafMeshes[i]), in two steps: describe() takes the leaves'
    // ranges, boxes, convexity and colours (tree.leaves[i].color), which
    // leaf() and the rest answer from then on; fill() then writes the
    // buffers, a slice of leaves at a time. `release` (`model` itself, or
    // null): let each mesh go (release->leafMeshes[i] left empty) as it is
    // read, and hand the freed memory back to the system, so that a million
    // leaves never hold their meshes and their buffers at once.
    void describe(const scene::Tree& tree, const model::Model& model);
    void fill(const model::Model& model, model::Model* release);

    // glDrawElements of leaf `leaf`'s triangles; either vertex array must be bound.
    void drawLeaf(int leaf) const;

    const gpu::VertexArray& vertexArray() const { return vertexArray_; }
    const gpu::VertexArray& memberVertexArray() const { return memberVertexArray_; }
    // The most draws one multi-draw over memberVertexArray() can number.
    static constexpr std::size_t kMostMembers = 65536;
    // A multi-draw's records for `leaves` (at most kMostMembers), in order:
    // draw m draws leaves[m] with base instance m.
    std::vector<DrawElementsIndirectCommand> memberCommands(std::span<const int> leaves) const;
    const gpu::VertexArray& leafVertexArray() const { return leafVertexArray_; }
    // The most leaves leafVertexArray() can number exactly (as floats).
    static constexpr std::size_t kMostLeafNumbers = (std::size_t(1) << 24) - 1;
    // A multi-draw's records for `leaves` over leafVertexArray(), in order,
    // leaves without triangles left out: leaf i's draw has base instance i.
    std::vector<DrawElementsIndirectCommand> leafCommands(std::span<const int> leaves) const;
    // leafVertexArray()'s attributes over another index buffer, one that
    // indexes the scene's vertices as the scene's own does (a subset of
    // its triangles, leafTriangles' indices).
    gpu::VertexArray leafVertexArrayOver(const gpu::Buffer& indices) const;
    // Leaf `leaf`'s triangles as drawn, read back from the buffers: three
    // entries of the index buffer each, and their corners' positions.
    struct LeafTriangles {
        std::vector<std::uint32_t> indices;
        std::vector<glm::vec3> corners;
    };
    LeafTriangles leafTriangles(int leaf) const;
    // Per leaf: its color() in rgba, a = -1 when it has none.
    const std::vector<glm::vec4>& leafColors() const { return leafColors_; }
    const std::vector<LeafRange>& leaves() const { return leaves_; }
    const LeafRange& leaf(int index) const { return leaves_[static_cast<std::size_t>(index)]; }
    // Of every leaf with triangles, background leaves included.
    const mesh::Bounds& bounds() const { return bounds_; }
    // Hashes the face planes of the convex `leaves` (model as in describe),
    // for shareAPlane; leaves not hashed have no planes there.
    void hashPlanes(const model::Model& model, const std::vector<int>& leaves);
    // Whether two of the convex `leaves` have faces in one plane, facing the
    // same way (to a billionth of the scene's size): where members of an
    // intersection group can tie (GroupPeel.h). Remembered per set of leaves.
    bool shareAPlane(const std::vector<int>& leaves) const;
    // Leaf `leaf`'s vertices (world space, as uploaded), for screen rectangles.
    std::span<const glm::vec3> leafVertices(int leaf) const;
    std::size_t bytes() const;

private:
    gpu::Buffer positions_;
    gpu::Buffer indices_;  // the layout's triangles
    gpu::Buffer facePlaneBuffer_;  // attribute 1
    FacePlanes facePlanes_;        // from describe() to fill()
    void setSurfaceAttributes(gpu::VertexArray& array) const;  // attributes 0 and 1
    gpu::VertexArray vertexArray_;
    gpu::Buffer memberNumbers_;  // 0, 1, 2, ... as floats: attribute 2 of memberVertexArray_
    gpu::VertexArray memberVertexArray_;
    gpu::VertexArray leafVertexArray_;
    std::vector<LeafRange> leaves_;
    std::vector<std::vector<std::uint64_t>> planes_;  // per leaf hashed: its faces' planes, sorted
    mutable std::map<std::vector<int>, bool> sharing_;  // shareAPlane's answers
    std::vector<glm::vec4> leafColors_;
    std::vector<glm::vec3> vertices_;          // all leaves' vertices, as in positions_
    std::vector<std::size_t> firstVertex_;     // per leaf, and one past the last
    std::vector<std::uint32_t> layoutStart_;   // per leaf, and one past the last: into the layouts' vertices
    mesh::Bounds bounds_;
};

// Sets surface.vert's uniforms (the view) on `program`, a program whose
// vertex stage it is; `tileOrigin`: the frame pixel at gl_FragCoord (0, 0)
// (a pass that draws one tile with its viewport moved by -tile).
void setSurfaceView(gpu::Program& program, const ViewSetup& view, glm::ivec2 tileOrigin = {0, 0});

}  // namespace strata::render
