#include "strata/contour/Planes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace strata::contour {
namespace {

// Normals are bucketed on a grid of this many cells per unit of each
// component; a query looks in the buckets within kNormalSpread of its
// normal (one or two along each axis).
constexpr double kCellsPerUnit = 32.0;

// Two triangles' planes are one where their normals differ by at most this
// and their offsets by this times the meshes' extent.
constexpr double kMergeNormal = 1e-7;
constexpr double kMergeOffset = 1e-7;

// How far apart, at most, two unit normals within kNormalMatch are.
const double kNormalSpread = std::sqrt(2.0 * (1.0 - PlaneTable::kNormalMatch));

}  // namespace

PlaneTable::Key PlaneTable::keyOf(const glm::ivec3& cell) {
    const auto part = [](int c) { return std::uint64_t(std::uint32_t(c + 1024) & 0xfffff); };
    return part(cell.x) | part(cell.y) << 20 | part(cell.z) << 40;
}

glm::ivec3 PlaneTable::cellOf(const glm::dvec3& normal) {
    return glm::ivec3(glm::floor(normal * kCellsPerUnit));
}

PlaneTable PlaneTable::fromMeshes(std::span<const mesh::Mesh> meshes) {
    mesh::Bounds box;
    for (const mesh::Mesh& m : meshes) box.extend(mesh::boundsOf(m));
    PlaneTable table;
    if (box.empty()) return table;
    table.mergeTolerance_ = kMergeOffset * std::max(box.diagonal(), glm::length(box.center()));
    for (const mesh::Mesh& m : meshes) {
        // Where each of the mesh's triangles went (plane pair, place in its
        // list), for the planes across its edges.
        constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
        std::vector<std::pair<std::size_t, std::size_t>> placed(m.triangles.size(), {kNone, 0});
        for (std::size_t f = 0; f < m.triangles.size(); ++f) {
            const auto& t = m.triangles[f];
            const glm::dvec3& a = m.positions[t[0]];
            const glm::dvec3 n = glm::cross(m.positions[t[1]] - a, m.positions[t[2]] - a);
            const double length = glm::length(n);
            if (!(length > 0.0) || !std::isfinite(length)) continue;
            const glm::dvec3 unit = n / length;
            const std::int32_t id = table.add(Plane{unit, glm::dot(unit, a)});
            const glm::dvec3& b = m.positions[t[1]];
            const glm::dvec3& c = m.positions[t[2]];
            std::vector<Triangle>& list = table.triangles_[std::size_t(id / 2)];
            placed[f] = {std::size_t(id / 2), list.size()};
            list.push_back(Triangle{{a, b, c}, unit, glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)), id, {}});
            list.back().across.fill(-1);
        }
        // Each edge's two triangles (a closed mesh has two per edge).
        std::unordered_map<std::uint64_t, std::array<std::pair<std::size_t, int>, 2>> byEdge;
        std::unordered_map<std::uint64_t, int> uses;
        for (std::size_t f = 0; f < m.triangles.size(); ++f) {
            if (placed[f].first == kNone) continue;
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t u = m.triangles[f][std::size_t(e)], v = m.triangles[f][std::size_t((e + 1) % 3)];
                const std::uint64_t key = (std::uint64_t(std::min(u, v)) << 32) | std::max(u, v);
                const int n = uses[key]++;
                if (n < 2) byEdge[key][std::size_t(n)] = {f, e};
            }
        }
        for (const auto& [key, pair] : byEdge) {
            if (uses[key] != 2) continue;
            Triangle& x = table.triangles_[placed[pair[0].first].first][placed[pair[0].first].second];
            Triangle& y = table.triangles_[placed[pair[1].first].first][placed[pair[1].first].second];
            if (placed[pair[0].first].first == placed[pair[1].first].first) continue;  // one plane
            x.across[std::size_t(pair[0].second)] = y.facing;
            y.across[std::size_t(pair[1].second)] = x.facing;
        }
    }
    return table;
}

std::int32_t PlaneTable::add(const Plane& plane) {
    std::int32_t known = -1;
    visit(plane.normal, plane.offset - mergeTolerance_, plane.offset + mergeTolerance_, [&](std::int32_t id) {
        if (known < 0 && glm::length(planes_[std::size_t(id)].normal - plane.normal) <= kMergeNormal) known = id;
    });
    if (known >= 0) return known;
    const auto id = std::int32_t(planes_.size());
    insert(plane);
    insert(Plane{-plane.normal, -plane.offset});
    triangles_.emplace_back();
    return id;
}

bool PlaneTable::onTriangle(std::int32_t id, const glm::dvec3& point, double tolerance) const {
    for (const Triangle& t : triangles_[std::size_t(id / 2)]) {
        if (glm::any(glm::lessThan(point, t.low - tolerance)) || glm::any(glm::greaterThan(point, t.high + tolerance)))
            continue;
        bool inside = true;
        for (std::size_t e = 0; e < 3 && inside; ++e) {
            const glm::dvec3& a = t.corners[e];
            const glm::dvec3 edge = t.corners[(e + 1) % 3] - a;
            // Signed distance of `point` from the edge's line, inward positive.
            inside = glm::dot(glm::cross(edge, point - a), t.normal) >= -tolerance * glm::length(edge);
        }
        if (inside) return true;
    }
    return false;
}

std::int32_t PlaneTable::acrossEdge(std::int32_t id, const glm::dvec3& point, double reach, double tolerance) const {
    for (const Triangle& t : triangles_[std::size_t(id / 2)]) {
        if (glm::any(glm::lessThan(point, t.low - reach)) || glm::any(glm::greaterThan(point, t.high + reach))) continue;
        for (const std::int32_t outward : t.across) {
            if (outward < 0) continue;
            // The facing `id` has against this triangle's, carried across.
            const std::int32_t other = id == t.facing ? outward : outward ^ 1;
            const Plane& plane = planes_[std::size_t(other)];
            if (!(std::abs(glm::dot(plane.normal, point) - plane.offset) <= reach)) continue;
            if (onTriangle(other, point, tolerance)) return other;
        }
    }
    return -1;
}

void PlaneTable::insert(const Plane& plane) {
    const auto id = std::int32_t(planes_.size());
    planes_.push_back(plane);
    std::vector<std::int32_t>& bucket = byDirection_[keyOf(cellOf(plane.normal))];
    const auto at = std::upper_bound(bucket.begin(), bucket.end(), plane.offset, [&](double o, std::int32_t other) {
        return o < planes_[std::size_t(other)].offset;
    });
    bucket.insert(at, id);
}

template <typename Visit>
void PlaneTable::visit(const glm::dvec3& normal, double low, double high, Visit&& visitPlane) const {
    // The buckets that normals within kNormalSpread of this one fall in.
    const glm::ivec3 first = cellOf(normal - glm::dvec3(kNormalSpread));
    const glm::ivec3 last = cellOf(normal + glm::dvec3(kNormalSpread));
    for (int z = first.z; z <= last.z; ++z) {
        for (int y = first.y; y <= last.y; ++y) {
            for (int x = first.x; x <= last.x; ++x) {
                const auto found = byDirection_.find(keyOf(glm::ivec3(x, y, z)));
                if (found == byDirection_.end()) continue;
                const std::vector<std::int32_t>& ids = found->second;
                auto it = std::lower_bound(ids.begin(), ids.end(), low, [&](std::int32_t id, double o) {
                    return planes_[std::size_t(id)].offset < o;
                });
                for (; it != ids.end() && planes_[std::size_t(*it)].offset <= high; ++it) visitPlane(*it);
            }
        }
    }
}

std::int32_t PlaneTable::find(const glm::dvec3& point, const glm::dvec3& normal, double tolerance) const {
    const double along = glm::dot(normal, point);
    const double window = tolerance + kNormalSpread * glm::length(point);
    std::int32_t best = -1;
    double bestDistance = tolerance;
    visit(normal, along - window, along + window, [&](std::int32_t id) {
        const Plane& plane = planes_[std::size_t(id)];
        if (glm::dot(plane.normal, normal) < kNormalMatch) return;
        const double distance = std::abs(glm::dot(plane.normal, point) - plane.offset);
        if (distance <= bestDistance) {
            bestDistance = distance;
            best = id;
        }
    });
    return best;
}

}  // namespace strata::contour
