#include "strata/mesh/MeshCheck.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <optional>
#include <unordered_map>
#include <array>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace strata::mesh {
namespace {

// A position as three integers: the bit patterns of its coordinates, with -0
// read as +0. Equal keys are exactly equal positions, and the order is total
// even with NaN about.
using PositionKey = std::array<uint64_t, 3>;

PositionKey keyOf(const glm::dvec3& p) {
    PositionKey k;
    for (int i = 0; i < 3; ++i) {
        const double d = p[i] + 0.0;  // -0 -> +0
        std::memcpy(&k[std::size_t(i)], &d, sizeof d);
    }
    return k;
}

// canonical[i]: the first vertex at positions[i]'s position. Sorting, not
// hashing: about ten times faster on large meshes here.
std::vector<uint32_t> canonicalVertices(const std::vector<glm::dvec3>& positions) {
    std::vector<std::pair<PositionKey, uint32_t>> order(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) order[i] = {keyOf(positions[i]), static_cast<uint32_t>(i)};
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> canonical(positions.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const bool startsRun = i == 0 || order[i].first != order[i - 1].first;
        canonical[order[i].second] = startsRun ? order[i].second : canonical[order[i - 1].second];
    }
    return canonical;
}

uint64_t edgeKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

bool hasRepeatedVertex(const std::array<uint32_t, 3>& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// The triangles that traverse a directed edge, for dropDegenerateTriangles,
// which edits a few triangles of a large list: the edges of all of them
// sorted once (a map of a vector per edge cost seconds on a mesh of
// millions), and those of triangles edited since in a small map. An entry
// is only a hint: a triangle counts if it is alive and has the edge now.
class EdgeIndex {
public:
    EdgeIndex(const std::vector<std::array<uint32_t, 3>>& tris, const std::vector<bool>& dead) : tris_(tris), dead_(dead) {
        sorted_.reserve(3 * tris.size());
        for (std::size_t t = 0; t < tris.size(); ++t) {
            if (dead[t]) continue;
            for (int k = 0; k < 3; ++k) sorted_.emplace_back(edgeKey(tris[t][k], tris[t][(k + 1) % 3]), t);
        }
        std::sort(sorted_.begin(), sorted_.end());
    }
    // Triangle t as it is now (new, or edited in place).
    void add(std::size_t t) {
        for (int k = 0; k < 3; ++k) added_[edgeKey(tris_[t][k], tris_[t][(k + 1) % 3])].push_back(t);
    }
    // The live triangles that traverse a -> b.
    std::vector<std::size_t> traversing(uint32_t a, uint32_t b) const {
        const uint64_t key = edgeKey(a, b);
        std::vector<std::size_t> out;
        auto consider = [&](std::size_t t) {
            if (t >= tris_.size() || dead_[t] || !traverses(tris_[t], a, b)) return;
            if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
        };
        auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(key, std::size_t(0)));
        for (; it != sorted_.end() && it->first == key; ++it) consider(it->second);
        if (const auto extra = added_.find(key); extra != added_.end()) {
            for (std::size_t t : extra->second) consider(t);
        }
        return out;
    }

private:
    static bool traverses(const std::array<uint32_t, 3>& t, uint32_t a, uint32_t b) {
        for (int k = 0; k < 3; ++k) {
            if (t[k] == a && t[(k + 1) % 3] == b) return true;
        }
        return false;
    }
    const std::vector<std::array<uint32_t, 3>>& tris_;
    const std::vector<bool>& dead_;
    std::vector<std::pair<uint64_t, std::size_t>> sorted_;
    std::unordered_map<uint64_t, std::vector<std::size_t>> added_;
};

// Scales v by a power of two (exactly) so its largest component is in [0.5, 1):
// the zero-area test below then does not underflow for tiny triangles.
glm::dvec3 normalizedExponent(const glm::dvec3 v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (m == 0.0 || !std::isfinite(m)) return v;
    int e = 0;
    std::frexp(m, &e);
    return {std::ldexp(v.x, -e), std::ldexp(v.y, -e), std::ldexp(v.z, -e)};
}

bool exactlyCollinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(normalizedExponent(b - a), normalizedExponent(c - a));
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

}  // namespace

std::string MeshCheck::describe() const {
    std::string s;
    auto add = [&s](const std::string& part) { s += (s.empty() ? "" : "; ") + part; };
    auto edges = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " edge" : " edges"); };
    if (boundaryEdges > 0) add("not closed: " + std::to_string(boundaryEdges) + (boundaryEdges == 1 ? " boundary edge" : " boundary edges"));
    if (nonManifoldEdges > 0) add("not manifold: " + edges(nonManifoldEdges) + " shared by more than two triangles");
    if (misorientedEdges > 0) add("inconsistently oriented: " + edges(misorientedEdges));
    if (inwardOriented) add("inward oriented (negative volume)");
    return s;
}

MeshCheck checkMesh(const Mesh& mesh) {
    MeshCheck check;
    const auto canonical = canonicalVertices(mesh.positions);
    const std::size_t vertexCount = mesh.positions.size();

    // Directed edges grouped by their start vertex (compressed rows), each
    // row sorted: then how often a->b and b->a occur are two binary searches.
    std::vector<uint32_t> rowStart(vertexCount + 1, 0);
    glm::dvec3 origin(0.0);
    if (!mesh.positions.empty()) origin = boundsOf(mesh).center();
    double volume6 = 0.0;
    auto canonicalTriangle = [&](const std::array<uint32_t, 3>& tri) {
        return std::array<uint32_t, 3>{canonical[tri[0]], canonical[tri[1]], canonical[tri[2]]};
    };
    for (const auto& tri : mesh.triangles) {
        const auto t = canonicalTriangle(tri);
        if (hasRepeatedVertex(t)) continue;
        for (uint32_t v : t) ++rowStart[v + 1];
        const glm::dvec3 p0 = mesh.positions[t[0]] - origin;
        const glm::dvec3 p1 = mesh.positions[t[1]] - origin;
        const glm::dvec3 p2 = mesh.positions[t[2]] - origin;
        volume6 += glm::dot(p0, glm::cross(p1, p2));
    }
    for (std::size_t v = 0; v < vertexCount; ++v) rowStart[v + 1] += rowStart[v];
    std::vector<uint32_t> target(rowStart[vertexCount]);
    std::vector<uint32_t> fill(rowStart.begin(), rowStart.end() - 1);
    for (const auto& tri : mesh.triangles) {
        const auto t = canonicalTriangle(tri);
        if (hasRepeatedVertex(t)) continue;
        for (int k = 0; k < 3; ++k) target[fill[t[k]]++] = t[(k + 1) % 3];
    }
    auto row = [&](uint32_t v) { return std::pair(target.begin() + rowStart[v], target.begin() + rowStart[v + 1]); };
    for (uint32_t v = 0; v < vertexCount; ++v) {
        auto [b, e] = row(v);
        std::sort(b, e);
    }
    for (uint32_t v = 0; v < vertexCount; ++v) {
        auto [b, e] = row(v);
        for (auto it = b; it != e;) {
            const uint32_t w = *it;
            const auto runEnd = std::upper_bound(it, e, w);
            const auto forward = static_cast<std::size_t>(runEnd - it);
            it = runEnd;
            auto [wb, we] = row(w);
            const auto backward = static_cast<std::size_t>(std::upper_bound(wb, we, v) - std::lower_bound(wb, we, v));
            if (v > w && backward > 0) continue;  // counted from w's row
            const std::size_t total = forward + backward;
            if (total == 1) ++check.boundaryEdges;
            else if (total > 2 && forward == backward) ++check.touchingEdges;
            else if (total > 2) ++check.nonManifoldEdges;
            else if (forward != 1) ++check.misorientedEdges;
        }
    }
    check.inwardOriented = check.boundaryEdges == 0 && check.nonManifoldEdges == 0 && check.misorientedEdges == 0 &&
                           volume6 < 0.0;
    return check;
}

void mergeCoincidentVertices(Mesh& mesh) {
    const auto canonical = canonicalVertices(mesh.positions);
    std::vector<uint32_t> remap(mesh.positions.size());
    std::vector<glm::dvec3> kept;
    kept.reserve(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        if (canonical[i] == i) {
            remap[i] = static_cast<uint32_t>(kept.size());
            kept.push_back(mesh.positions[i]);
        } else {
            remap[i] = remap[canonical[i]];
        }
    }
    for (auto& t : mesh.triangles)
        for (auto& v : t) v = remap[v];
    mesh.positions = std::move(kept);
}

// Long, and kept in one piece: one pass over a triangle list that it edits
// in place (slivers split across their long edge, the edge index told of
// each edit, then triangles and vertices compacted); the pieces share it.
void dropDegenerateTriangles(Mesh& mesh) {
    mergeCoincidentVertices(mesh);
    auto& tris = mesh.triangles;
    std::vector<bool> dead(tris.size(), false);
    for (std::size_t i = 0; i < tris.size(); ++i) dead[i] = hasRepeatedVertex(tris[i]);

    std::deque<std::size_t> slivers;
    auto isSliver = [&](std::size_t t) {
        const auto& v = tris[t];
        return exactlyCollinear(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]);
    };
    bool anySliver = false;
    for (std::size_t t = 0; t < tris.size(); ++t) {
        if (!dead[t] && isSliver(t)) {
            slivers.push_back(t);
            anySliver = true;
        }
    }
    // Directed edge -> triangles traversing it, as slivers are split.
    std::optional<EdgeIndex> byEdge;
    if (anySliver) byEdge.emplace(tris, dead);
    // Each split removes one sliver and adds two triangles; bound the work in
    // case a pathological input keeps producing slivers.
    std::size_t budget = 4 * tris.size() + 16;
    while (!slivers.empty() && budget-- > 0) {
        const std::size_t s = slivers.front();
        slivers.pop_front();
        if (dead[s]) continue;
        // Rotate so the sliver reads (x, m, y) with m between x and y: the long
        // edge is y->x, and the triangle across it traverses x->y.
        auto v = tris[s];
        auto len2 = [&](uint32_t a, uint32_t b) {
            const glm::dvec3 d = mesh.positions[a] - mesh.positions[b];
            return glm::dot(d, d);
        };
        int middle = 0;
        double best = -1.0;
        for (int k = 0; k < 3; ++k) {
            const double l = len2(v[(k + 1) % 3], v[(k + 2) % 3]);  // edge opposite v[k]
            if (l > best) best = l, middle = k;
        }
        const uint32_t m = v[middle], y = v[(middle + 1) % 3], x = v[(middle + 2) % 3];
        dead[s] = true;
        const std::vector<std::size_t> across = byEdge->traversing(x, y);
        if (across.size() != 1) continue;  // no single neighbour: just drop it
        const std::size_t n = across.front();
        auto nv = tris[n];
        int k = 0;
        while (!(nv[k] == x && nv[(k + 1) % 3] == y)) ++k;
        const uint32_t z = nv[(k + 2) % 3];
        tris[n] = {x, m, z};
        tris.push_back({m, y, z});
        dead.push_back(false);
        for (std::size_t t : {n, tris.size() - 1}) {
            if (hasRepeatedVertex(tris[t])) {
                dead[t] = true;
                continue;
            }
            byEdge->add(t);
            if (isSliver(t)) slivers.push_back(t);
        }
    }
    // Slivers left over (budget spent) are dropped as they are.
    for (std::size_t s : slivers) dead[s] = true;

    // Compact triangles, then vertices.
    std::vector<std::array<uint32_t, 3>> kept;
    kept.reserve(tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
        if (!dead[t]) kept.push_back(tris[t]);
    // Unused vertices go; the others keep their order.
    std::vector<uint32_t> remap(mesh.positions.size(), UINT32_MAX);
    for (const auto& t : kept)
        for (uint32_t i : t) remap[i] = 0;
    std::vector<glm::dvec3> positions;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        if (remap[i] == UINT32_MAX) continue;
        remap[i] = static_cast<uint32_t>(positions.size());
        positions.push_back(mesh.positions[i]);
    }
    for (auto& t : kept)
        for (auto& i : t) i = remap[i];
    mesh.triangles = std::move(kept);
    mesh.positions = std::move(positions);
}

}  // namespace strata::mesh
