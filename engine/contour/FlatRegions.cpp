#include "FlatRegions.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

#include "Parallel.h"
#include "strata/core/Progress.h"

namespace strata::contour {
namespace {

constexpr std::uint32_t kDead = std::numeric_limits<std::uint32_t>::max();

bool holds(const VertexPlanes& planes, std::int32_t id) {
    return id >= 0 && std::find(planes.begin(), planes.end(), id) != planes.end();
}

// Slabs along z for the parallel passes: a collapse whose vertices all lie
// in one slab touches nothing another slab's collapses touch.
constexpr int kSlabs = 64;
constexpr int kAnySlab = -1;

// Reported after each pass: the vertices removed so far, of all the
// contour's (the count a merge ends at is not known before it ends).
constexpr const char* kProgressWhat = "contour: flat regions";

class Merger {
public:
    // Reads `positions` and `vertexPlanes`, which must outlive it; works on
    // its own copy of the triangles.
    Merger(const std::vector<glm::dvec3>& positions, std::vector<std::array<std::uint32_t, 3>> triangles,
           const std::vector<VertexPlanes>& vertexPlanes, const PlaneTable& planes)
        : positions_(positions), triangles_(std::move(triangles)), vertexPlanes_(vertexPlanes), planes_(planes) {}

    std::size_t run();
    mesh::Mesh result();

private:
    // One thread's scratch.
    struct Scratch {
        std::vector<std::uint32_t> ringU, ringV;
        std::vector<std::pair<double, std::uint32_t>> candidates;
    };

    std::int32_t labelOf(const std::array<std::uint32_t, 3>& t) const;
    // One pass over `live` (dropping the vertices that can no longer go),
    // collapsing only within `slab` unless kAnySlab; returns the collapses.
    std::size_t pass(std::vector<std::uint32_t>& live, int slab, Scratch& scratch);
    bool tryRemove(std::uint32_t u, int slab, Scratch& scratch);
    // A vertex with a triangle on no plane stays: that triangle never goes
    // (only triangles on planes are dropped by a collapse).
    bool fixed(std::uint32_t u) const {
        for (const std::uint32_t f : faces_[u]) {
            if (label_[f] < 0) return true;
        }
        return false;
    }
    bool inSlab(const std::vector<std::uint32_t>& vertices, int slab) const {
        if (slab == kAnySlab) return true;
        for (const std::uint32_t w : vertices) {
            if (slab_[w] != slab) return false;
        }
        return true;
    }
    void neighboursOf(std::uint32_t v, std::vector<std::uint32_t>& out) const;
    // The least shape of the triangles around `u` with `u` replaced by `v`
    // (those holding both are dropped); -1 where one would turn over, leave
    // its plane or fall below kMinMergedShape.
    double shapeAfterCollapse(std::uint32_t u, std::uint32_t v) const;
    void collapse(std::uint32_t u, std::uint32_t v);
    void forget(std::uint32_t vertex, std::uint32_t face);

    const std::vector<glm::dvec3>& positions_;
    std::vector<std::array<std::uint32_t, 3>> triangles_;
    const std::vector<VertexPlanes>& vertexPlanes_;
    const PlaneTable& planes_;
    std::vector<std::int32_t> label_;                 // per triangle: its plane, or -1
    std::vector<std::vector<std::uint32_t>> faces_;   // per vertex: its live triangles
    std::vector<std::uint8_t> touched_;               // per vertex: next to a collapse of this pass
    std::vector<std::uint8_t> changed_;               // per vertex: its ring changed since its last try
    std::vector<std::uint8_t> slab_;                  // per vertex: its slab along z
};

std::int32_t Merger::labelOf(const std::array<std::uint32_t, 3>& t) const {
    const VertexPlanes& a = vertexPlanes_[t[0]];
    for (const std::int32_t id : a) {
        if (id < 0 || !holds(vertexPlanes_[t[1]], id) || !holds(vertexPlanes_[t[2]], id)) continue;
        const auto& p = positions_;
        const glm::dvec3 n = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
        return glm::dot(n, planes_[id].normal) >= 0.0 ? id : -1;
    }
    return -1;
}

std::size_t Merger::run() {
    const std::size_t vertices = positions_.size();
    label_.resize(triangles_.size());
    faces_.resize(vertices);
    std::vector<std::uint32_t> degree(vertices, 0);
    for (const auto& t : triangles_) {
        for (const std::uint32_t v : t) ++degree[v];
    }
    for (std::size_t v = 0; v < vertices; ++v) faces_[v].reserve(degree[v]);
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
        label_[f] = labelOf(triangles_[f]);
        for (const std::uint32_t v : triangles_[f]) faces_[v].push_back(std::uint32_t(f));
    }
    touched_.assign(vertices, 0);
    changed_.assign(vertices, 1);
    // Passes over the vertices in which no two collapses touch: each pass
    // removes about every other vertex of a flat region, and the regions'
    // fans stay small until the last passes (collapsing as they come would
    // grow a few vertices into hubs that every later try pays for). First
    // within slabs along z, in parallel, while the fans are small; then
    // over all that is left. Each slab's vertices go in index order, so the
    // result does not depend on the number of threads.
    double low = 1e300, high = -1e300;
    for (const glm::dvec3& p : positions_) low = std::min(low, p.z), high = std::max(high, p.z);
    const double scale = high > low ? kSlabs / (high - low) : 0.0;
    slab_.resize(vertices);
    std::vector<std::vector<std::uint32_t>> live(kSlabs);
    for (std::uint32_t v = 0; v < vertices; ++v) {
        slab_[v] = std::uint8_t(std::clamp(int((positions_[v].z - low) * scale), 0, kSlabs - 1));
        live[slab_[v]].push_back(v);
    }
    std::size_t removed = 0;
    reportProgress(kProgressWhat, 0, vertices);
    for (std::size_t collapses = 1; collapses > 0;) {
        collapses = 0;
        STRATA_FOR_PIECES_SUM(collapses)
        for (int slab = 0; slab < kSlabs; ++slab) {
            Scratch scratch;
            collapses += pass(live[std::size_t(slab)], slab, scratch);
        }
        removed += collapses;
        reportProgress(kProgressWhat, removed, vertices);
    }
    std::vector<std::uint32_t> all;
    for (const auto& piece : live) all.insert(all.end(), piece.begin(), piece.end());
    std::sort(all.begin(), all.end());
    // Tries the slabs refused (rings across two slabs) are worth again.
    for (const std::uint32_t u : all) changed_[u] = 1;
    Scratch scratch;
    for (std::size_t collapses = 1; collapses > 0;) {
        collapses = pass(all, kAnySlab, scratch);
        removed += collapses;
        reportProgress(kProgressWhat, removed, vertices);
    }
    reportProgress(kProgressWhat, vertices, vertices);
    return removed;
}

std::size_t Merger::pass(std::vector<std::uint32_t>& live, int slab, Scratch& scratch) {
    for (const std::uint32_t u : live) touched_[u] = 0;
    std::size_t kept = 0, collapses = 0;
    for (const std::uint32_t u : live) {
        if (faces_[u].empty() || fixed(u)) continue;
        live[kept++] = u;
        if (touched_[u] || !changed_[u]) continue;
        changed_[u] = 0;
        if (tryRemove(u, slab, scratch)) ++collapses;
    }
    live.resize(kept);
    return collapses;
}

// In no particular order. A ring is small (six in a flat region of the
// contour) until the last passes, where a face's fan can reach hundreds.
void Merger::neighboursOf(std::uint32_t v, std::vector<std::uint32_t>& out) const {
    out.clear();
    constexpr std::size_t kSmallFan = 16;
    const bool small = faces_[v].size() <= kSmallFan;
    for (const std::uint32_t f : faces_[v]) {
        for (const std::uint32_t w : triangles_[f]) {
            if (w != v && (!small || std::find(out.begin(), out.end(), w) == out.end())) out.push_back(w);
        }
    }
    if (small) return;
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool Merger::tryRemove(std::uint32_t u, int slab, Scratch& scratch) {
    neighboursOf(u, scratch.ringU);
    if (!inSlab(scratch.ringU, slab)) return false;
    // The neighbours it may collapse into, best shape first.
    scratch.candidates.clear();
    for (const std::uint32_t v : scratch.ringU) {
        const double shape = shapeAfterCollapse(u, v);
        if (shape >= kMinMergedShape) scratch.candidates.push_back({shape, v});
    }
    std::sort(scratch.candidates.begin(), scratch.candidates.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [shape, v] : scratch.candidates) {
        neighboursOf(v, scratch.ringV);
        if (!inSlab(scratch.ringV, slab)) continue;
        // The two rings may share only the edge's two opposite vertices.
        std::size_t shared = 0;
        for (const std::uint32_t w : scratch.ringV) {
            shared += std::find(scratch.ringU.begin(), scratch.ringU.end(), w) != scratch.ringU.end() ? 1 : 0;
        }
        if (shared != 2) continue;
        collapse(u, v);
        // The vertices around both wait for the next pass, and are worth
        // trying again there.
        for (const std::uint32_t w : scratch.ringU) touched_[w] = changed_[w] = 1;
        for (const std::uint32_t w : scratch.ringV) touched_[w] = changed_[w] = 1;
        return true;
    }
    return false;
}

double Merger::shapeAfterCollapse(std::uint32_t u, std::uint32_t v) const {
    const auto& p = positions_;
    std::size_t dropped = 0;
    double least = std::numeric_limits<double>::max();
    for (const std::uint32_t f : faces_[u]) {
        std::array<std::uint32_t, 3> t = triangles_[f];
        if (t[0] == v || t[1] == v || t[2] == v) {
            ++dropped;
            continue;
        }
        const std::int32_t id = label_[f];
        if (!holds(vertexPlanes_[v], id)) return -1.0;
        for (std::uint32_t& w : t) w = w == u ? v : w;
        const glm::dvec3 n = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
        const double longest = longestEdgeSquared(p[t[0]], p[t[1]], p[t[2]]);
        if (!(longest > 0.0)) return -1.0;
        least = std::min(least, glm::dot(n, planes_[id].normal) / longest);
        // Not a collapse to take: no need to know by how much.
        if (least < kMinMergedShape) return -1.0;
    }
    // An edge of a closed 2-manifold has exactly two triangles.
    return dropped == 2 ? least : -1.0;
}

void Merger::forget(std::uint32_t vertex, std::uint32_t face) {
    std::vector<std::uint32_t>& list = faces_[vertex];
    list.erase(std::find(list.begin(), list.end(), face));
}

void Merger::collapse(std::uint32_t u, std::uint32_t v) {
    const std::vector<std::uint32_t> around = std::move(faces_[u]);
    faces_[u].clear();
    for (const std::uint32_t f : around) {
        std::array<std::uint32_t, 3>& t = triangles_[f];
        if (t[0] == v || t[1] == v || t[2] == v) {
            for (const std::uint32_t w : t) {
                if (w != u) forget(w, f);
            }
            t = {kDead, kDead, kDead};
            continue;
        }
        for (std::uint32_t& w : t) w = w == u ? v : w;
        faces_[v].push_back(f);
    }
}

mesh::Mesh Merger::result() {
    mesh::Mesh out;
    std::vector<std::uint32_t> index(positions_.size(), kDead);
    for (std::size_t v = 0; v < positions_.size(); ++v) {
        if (faces_[v].empty()) continue;
        index[v] = std::uint32_t(out.positions.size());
        out.positions.push_back(positions_[v]);
    }
    for (const auto& t : triangles_) {
        if (t[0] == kDead) continue;
        out.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
    return out;
}

}  // namespace

mesh::Mesh mergeFlatRegions(const mesh::Mesh& mesh, const std::vector<VertexPlanes>& vertexPlanes,
                            const PlaneTable& planes, ContourStats& stats) {
    Merger merger(mesh.positions, mesh.triangles, vertexPlanes, planes);
    stats.mergedVertices += merger.run();
    return merger.result();
}

}  // namespace strata::contour
