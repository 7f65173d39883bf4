#include "SceneBuffers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "Convexity.h"
#include "ShaderInterface.h"
#include "strata/core/Error.h"
#include "strata/mesh/LastCorners.h"

namespace strata::render {

void setSurfaceView(gpu::Program& program, const ViewSetup& view, glm::ivec2 tileOrigin) {
    program.setUniform(shader::kSurfaceViewProjection, view.viewProjection);
    program.setUniform(shader::kSurfaceEye, view.eye);
    program.setUniform(shader::kSurfaceForward, view.forward);
    // A program whose fragments need no depth (normal.frag's TRUST_MARKS)
    // has the ray's uniforms optimized away.
    if (program.uniformLocation("uOrigin") < 0) return;
    // The ray through a fragment, P = O + s D with dot(D, f) = 1 and
    // dot(O - eye, f) = 0, so that s is the view depth; O and D affine in
    // gl_FragCoord.xy, as the inverse of the view-projection gives them on
    // the near plane (in double, once a pass).
    const glm::dmat4 inverse = glm::inverse(view.viewProjectionD);
    const glm::dvec3 eye = view.eyeD, f = view.forwardD;
    auto nearPoint = [&](double fragX, double fragY) {
        const double x = 2.0 * (fragX + tileOrigin.x) / view.width - 1.0;
        const double y = 2.0 * (fragY + tileOrigin.y) / view.height - 1.0;
        const glm::dvec4 p = inverse * glm::dvec4(x, y, -1.0, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const glm::dvec3 p0 = nearPoint(0.0, 0.0), px = nearPoint(1.0, 0.0) - p0, py = nearPoint(0.0, 1.0) - p0;
    glm::dvec3 origin[3], ray[3];
    if (view.orthographic) {
        origin[0] = p0 - glm::dot(p0 - eye, f) * f;
        origin[1] = px - glm::dot(px, f) * f;
        origin[2] = py - glm::dot(py, f) * f;
        ray[0] = f;
        ray[1] = ray[2] = glm::dvec3(0.0);
    } else {
        const double near = glm::dot(p0 - eye, f);
        origin[0] = eye;
        origin[1] = origin[2] = glm::dvec3(0.0);
        ray[0] = (p0 - eye) / near;
        ray[1] = px / near;
        ray[2] = py / near;
    }
    for (int k = 0; k < 3; ++k) {
        program.setUniform(shader::kSurfaceOrigin + k, glm::vec3(origin[k]));
        program.setUniform(shader::kSurfaceRay + k, glm::vec3(ray[k]));
    }
}

FacePlanes::FacePlanes(const mesh::Bounds& scene)
    : unit_(std::max(scene.empty() ? 1.0 : scene.diagonal(), 1e-300) * 1e-9) {}

bool FacePlanes::keyOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, Key& key, glm::vec4& plane) const {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    const glm::dvec3 u = n / length;
    const double w = glm::dot(u, a);
    key = {std::llround(u.x * 1e9), std::llround(u.y * 1e9), std::llround(u.z * 1e9), std::llround(w / unit_)};
    plane = glm::vec4(glm::vec3(u), static_cast<float>(w));
    return true;
}

void FacePlanes::add(int leaf, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    Key key;
    glm::vec4 plane;
    if (!keyOf(a, b, c, key, plane)) return;
    const auto [at, added] = planes_.try_emplace(key, Entry{plane, leaf, false});
    if (!added && at->second.leaf != leaf) at->second.shared = true;
}

glm::vec4 FacePlanes::of(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
    Key key;
    glm::vec4 plane;
    if (!keyOf(a, b, c, key, plane)) return glm::vec4(0.0f);
    const auto at = planes_.find(key);
    if (at != planes_.end() && at->second.shared) return at->second.plane;
    return glm::vec4(glm::vec3(plane), shader::kOwnPlane);
}

std::uint64_t FacePlanes::hashKey(const Key& k) {
    std::uint64_t h = 1469598103934665603ull;
    for (long long c : k) h = (h ^ static_cast<std::uint64_t>(c)) * 1099511628211ull;
    return h;
}

std::optional<std::uint64_t> FacePlanes::hashOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
    Key key;
    glm::vec4 plane;
    if (!keyOf(a, b, c, key, plane)) return std::nullopt;
    return hashKey(key);
}

void SceneBuffers::describe(const scene::Tree& tree, const model::Model& model) {
    if (model.leafMeshes.size() != tree.leaves.size()) {
        throw Error("renderer: the model has " + std::to_string(model.leafMeshes.size()) +
                    " leaf meshes for a tree of " + std::to_string(tree.leaves.size()) + " leaves");
    }
    vertices_.clear();
    std::size_t meshVertices = 0;
    for (const mesh::Mesh& mesh : model.leafMeshes) meshVertices += mesh.positions.size();
    vertices_.reserve(meshVertices);
    firstVertex_.assign(1, 0);
    firstVertex_.reserve(model.leafMeshes.size() + 1);
    leaves_.assign(model.leafMeshes.size(), {});
    leafColors_.clear();
    bounds_ = {};
    layoutStart_.assign(model.leafMeshes.size() + 1, 0);
    std::size_t layoutVertices = 0, indexCount = 0;
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        const mesh::Mesh& mesh = model.leafMeshes[i];
        const std::size_t copies = mesh::lastCornerLayout(mesh).source.size();
        if (layoutVertices + copies > 0xffffffffu) throw Error("renderer: more than 2^32 vertices");
        layoutStart_[i] = static_cast<std::uint32_t>(layoutVertices);
        layoutVertices += copies;
        LeafRange& range = leaves_[i];
        range.firstIndex = indexCount;
        range.indexCount = 3 * mesh.triangles.size();
        indexCount += range.indexCount;
        for (const glm::dvec3& p : mesh.positions) {
            vertices_.emplace_back(p);
            range.bounds.extend(p);
        }
        firstVertex_.push_back(vertices_.size());
        range.convex = range.indexCount > 0 && isConvexLeaf(tree.leaves[i].primitive, mesh);
        range.solidShells = range.convex || everyShellHasVolume(mesh);
        if (range.indexCount > 0) bounds_.extend(range.bounds);
        const auto& c = tree.leaves[i].color;
        leafColors_.push_back(c ? glm::vec4(*c) : glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    }
    layoutStart_.back() = static_cast<std::uint32_t>(layoutVertices);
    planes_.assign(leaves_.size(), {});  // hashed on demand: hashPlanes
    // Every triangle's plane, to know which planes two leaves share.
    facePlanes_ = FacePlanes(bounds_);
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        const mesh::Mesh& mesh = model.leafMeshes[i];
        for (const auto& t : mesh.triangles) {
            facePlanes_.add(static_cast<int>(i), mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        }
    }
    sharing_.clear();
}

void SceneBuffers::fill(const model::Model& model, model::Model* release) {
    // Each triangle ends on a vertex of its own (lastCornerLayout), which
    // carries its face plane: the provoking vertex of a flat varying.
    const std::size_t layoutVertices = layoutStart_.back();
    const std::size_t indexCount = leaves_.empty() ? 0 : leaves_.back().firstIndex + leaves_.back().indexCount;
    std::vector<float> positions;        // by 3, the layouts' vertices
    std::vector<float> planes;           // by 4, per layout vertex; a triangle's on its last corner
    std::vector<std::uint32_t> indices;  // #F by 3, absolute, in the layout
    // Leaf i's vertices, planes and triangles onto the arrays, which start
    // at layout vertex `base`.
    auto append = [&](std::size_t i, std::size_t base) {
        const mesh::Mesh& mesh = model.leafMeshes[i];
        const mesh::LastCornerLayout layout = mesh::lastCornerLayout(mesh);
        const std::uint32_t firstVertex = layoutStart_[i];
        for (std::uint32_t v : layout.source) {
            const glm::dvec3& p = mesh.positions[v];
            for (double c : {p.x, p.y, p.z}) positions.push_back(static_cast<float>(c));
        }
        const std::size_t first = 4 * (firstVertex - base);  // this leaf's first plane in the arrays
        planes.resize(positions.size() / 3 * 4, 0.0f);
        for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
            const auto& t = mesh.triangles[f];
            for (std::uint32_t v : layout.triangles[f]) indices.push_back(firstVertex + v);
            const glm::vec4 plane = facePlanes_.of(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
            const std::size_t last = first + 4 * layout.triangles[f][2];
            for (int c = 0; c < 4; ++c) planes[last + static_cast<std::size_t>(c)] = plane[c];
        }
    };
    if (release != nullptr) {
        // The whole arrays, each mesh let go once appended (and its memory
        // handed back now and then: glibc would keep it), then a buffer at a
        // time from them: GL storage is made whole at once, so made before
        // the meshes were gone it would hold both.
        positions.reserve(3 * layoutVertices);
        planes.reserve(4 * layoutVertices);
        indices.reserve(indexCount);
        for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
            append(i, 0);
            release->leafMeshes[i] = {};  // read no more
#ifdef __GLIBC__
            if ((i + 1) % 65536 == 0) malloc_trim(0);
#endif
        }
#ifdef __GLIBC__
        malloc_trim(0);
#endif
        positions_ = gpu::Buffer::fromSpan("scene positions", std::span<const float>(positions));
        positions = std::vector<float>();  // (= {} would keep the storage)
        facePlaneBuffer_ = gpu::Buffer::fromSpan("scene face planes", std::span<const float>(planes));
        planes = std::vector<float>();  // (= {} would keep the storage)
        indices_ = gpu::Buffer::fromSpan("scene indices", std::span<const std::uint32_t>(indices));
        indices = std::vector<std::uint32_t>();  // (= {} would keep the storage)
    } else {
        // A slice of leaves at a time: the arrays never stand whole beside the buffers.
        positions_ = gpu::Buffer("scene positions", layoutVertices * 3 * sizeof(float));
        facePlaneBuffer_ = gpu::Buffer("scene face planes", layoutVertices * 4 * sizeof(float));
        indices_ = gpu::Buffer("scene indices", indexCount * sizeof(std::uint32_t));
        std::size_t vertexOffset = 0, indexOffset = 0;  // where the slice goes, in vertices and indices
        auto flush = [&] {
            positions_.uploadSpan(std::span<const float>(positions), vertexOffset * 3 * sizeof(float));
            facePlaneBuffer_.uploadSpan(std::span<const float>(planes), vertexOffset * 4 * sizeof(float));
            indices_.uploadSpan(std::span<const std::uint32_t>(indices), indexOffset * sizeof(std::uint32_t));
            vertexOffset += positions.size() / 3;
            indexOffset += indices.size();
            positions.clear();
            planes.clear();
            indices.clear();
        };
        constexpr std::size_t kSliceVertices = 1 << 20;
        for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
            append(i, vertexOffset);
            if (positions.size() / 3 >= kSliceVertices) flush();
        }
        flush();
    }
    vertexArray_ = gpu::VertexArray("scene");
    setSurfaceAttributes(vertexArray_);
    vertexArray_.setElementBuffer(indices_);
    // Numbers for a group's members and for every leaf (floats: exact below 2^24).
    const std::size_t numbered = std::max(kMostMembers, leaves_.size());
    if (!memberNumbers_.id() || memberNumbers_.size() < numbered * sizeof(float)) {
        std::vector<float> numbers(numbered);
        for (std::size_t m = 0; m < numbers.size(); ++m) numbers[m] = static_cast<float>(m);
        memberNumbers_ = gpu::Buffer::fromSpan("scene member numbers", std::span<const float>(numbers), 0);
    }
    memberVertexArray_ = gpu::VertexArray("scene with member numbers");
    setSurfaceAttributes(memberVertexArray_);
    memberVertexArray_.setVertexBuffer(2, memberNumbers_, 0, sizeof(float));
    memberVertexArray_.setBindingDivisor(2, 1);
    memberVertexArray_.setAttribute(2, 2, 1, GL_FLOAT, 0);
    memberVertexArray_.setElementBuffer(indices_);
    leafVertexArray_ = leafVertexArrayOver(indices_);
    facePlanes_ = FacePlanes();
}

void SceneBuffers::setSurfaceAttributes(gpu::VertexArray& array) const {
    array.setVertexBuffer(0, positions_, 0, 3 * sizeof(float));
    array.setAttribute(0, 0, 3, GL_FLOAT, 0);
    array.setVertexBuffer(1, facePlaneBuffer_, 0, 4 * sizeof(float));
    array.setAttribute(1, 1, 4, GL_FLOAT, 0);
}

gpu::VertexArray SceneBuffers::leafVertexArrayOver(const gpu::Buffer& indices) const {
    gpu::VertexArray array("scene with face planes and leaf numbers");
    setSurfaceAttributes(array);
    array.setVertexBuffer(2, memberNumbers_, 0, sizeof(float));
    array.setBindingDivisor(2, 1);
    array.setAttribute(2, 2, 1, GL_FLOAT, 0);
    array.setElementBuffer(indices);
    return array;
}

SceneBuffers::LeafTriangles SceneBuffers::leafTriangles(int leaf) const {
    const auto i = static_cast<std::size_t>(leaf);
    const LeafRange& range = leaves_[i];
    LeafTriangles out;
    if (range.indexCount == 0) return out;
    out.indices.resize(range.indexCount);
    indices_.downloadSpan(std::span(out.indices), range.firstIndex * sizeof(std::uint32_t));
    const std::size_t first = layoutStart_[i], count = layoutStart_[i + 1] - first;
    std::vector<float> xyz(3 * count);
    positions_.downloadSpan(std::span(xyz), first * 3 * sizeof(float));
    out.corners.reserve(out.indices.size());
    for (std::uint32_t v : out.indices) {
        const std::size_t k = 3 * (v - first);
        out.corners.emplace_back(xyz[k], xyz[k + 1], xyz[k + 2]);
    }
    return out;
}

std::vector<DrawElementsIndirectCommand> SceneBuffers::leafCommands(std::span<const int> leaves) const {
    if (leaves_.size() > kMostLeafNumbers) throw Error("renderer: more than 2^24 - 1 leaves to number");
    std::vector<DrawElementsIndirectCommand> commands;
    commands.reserve(leaves.size());
    for (int leaf : leaves) {
        const LeafRange& range = leaves_[static_cast<std::size_t>(leaf)];
        if (range.indexCount == 0) continue;
        commands.push_back({static_cast<GLuint>(range.indexCount), 1, static_cast<GLuint>(range.firstIndex), 0,
                            static_cast<GLuint>(leaf)});
    }
    return commands;
}

std::vector<DrawElementsIndirectCommand> SceneBuffers::memberCommands(std::span<const int> leaves) const {
    if (leaves.size() > kMostMembers) throw Error("renderer: a group of more than 65536 members");
    std::vector<DrawElementsIndirectCommand> commands;
    commands.reserve(leaves.size());
    for (std::size_t m = 0; m < leaves.size(); ++m) {
        const LeafRange& range = leaves_[static_cast<std::size_t>(leaves[m])];
        commands.push_back({static_cast<GLuint>(range.indexCount), 1, static_cast<GLuint>(range.firstIndex), 0,
                            static_cast<GLuint>(m)});
    }
    return commands;
}

void SceneBuffers::drawLeaf(int leaf) const {
    const LeafRange& range = leaves_[static_cast<std::size_t>(leaf)];
    if (range.indexCount == 0) return;
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.indexCount), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(range.firstIndex * sizeof(std::uint32_t)));
}

void SceneBuffers::hashPlanes(const model::Model& model, const std::vector<int>& leaves) {
    // Planes as FacePlanes tells them apart, each hashed to one number.
    const FacePlanes planes(bounds_);
    for (int leaf : leaves) {
        const auto i = static_cast<std::size_t>(leaf);
        std::vector<std::uint64_t>& keys = planes_[i];
        if (!leaves_[i].convex || !keys.empty()) continue;
        const mesh::Mesh& mesh = model.leafMeshes[i];
        for (const auto& t : mesh.triangles) {
            if (const std::optional<std::uint64_t> key =
                    planes.hashOf(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]])) {
                keys.push_back(*key);
            }
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
    return positions_.size() + indices_.size() + facePlaneBuffer_.size();
}

}  // namespace strata::render
