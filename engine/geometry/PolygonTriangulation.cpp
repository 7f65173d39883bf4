#include "PolygonTriangulation.h"

#include <cmath>
#include <cstddef>

#include <glm/vec2.hpp>

namespace strata::geometry::detail {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// p inside or on the boundary of the counter-clockwise triangle (a, b, c).
bool inClosedTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0;
}

}  // namespace

void triangulatePolygon(const std::vector<glm::dvec3>& positions, std::span<const uint32_t> loop,
                        std::vector<std::array<uint32_t, 3>>& out) {
    // Drop consecutive repeats (also across the wrap).
    std::vector<uint32_t> v;
    v.reserve(loop.size());
    for (uint32_t i : loop) {
        if (v.empty() || positions[v.back()] != positions[i]) v.push_back(i);
    }
    while (v.size() > 1 && positions[v.back()] == positions[v.front()]) v.pop_back();
    if (v.size() < 3) return;
    if (v.size() == 3) {
        out.push_back({v[0], v[1], v[2]});
        return;
    }

    // Newell normal: robust for non-convex and slightly non-planar loops.
    glm::dvec3 n(0.0);
    const glm::dvec3 origin = positions[v[0]];
    for (std::size_t i = 0; i < v.size(); ++i) {
        const glm::dvec3 a = positions[v[i]] - origin;
        const glm::dvec3 b = positions[v[(i + 1) % v.size()]] - origin;
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    // Project by dropping the dominant axis; the two kept axes are taken in
    // cyclic order (and swapped when that axis is negative) so the loop stays
    // counter-clockwise in 2D.
    int k = 2;
    if (std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z)) k = 0;
    else if (std::abs(n.y) >= std::abs(n.z)) k = 1;
    int u = (k + 1) % 3, w = (k + 2) % 3;
    if (n[k] < 0.0) std::swap(u, w);
    std::vector<glm::dvec2> p(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        const glm::dvec3 q = positions[v[i]] - origin;
        p[i] = {q[u], q[w]};
    }

    // Ear clipping on a circular linked list.
    const std::size_t count = v.size();
    std::vector<std::size_t> next(count), prev(count);
    for (std::size_t i = 0; i < count; ++i) {
        next[i] = (i + 1) % count;
        prev[i] = (i + count - 1) % count;
    }
    auto strictlyConvex = [&](std::size_t i) { return cross2(p[prev[i]], p[i], p[next[i]]) > 0.0; };
    auto isEar = [&](std::size_t i) {
        const std::size_t a = prev[i], c = next[i];
        if (!strictlyConvex(i)) return false;
        // Only vertices that are not strictly convex can lie in an ear of a
        // simple polygon; vertices sharing a corner's position do not count.
        for (std::size_t j = next[c]; j != a; j = next[j]) {
            if (strictlyConvex(j)) continue;
            if (p[j] == p[a] || p[j] == p[i] || p[j] == p[c]) continue;
            if (inClosedTriangle(p[j], p[a], p[i], p[c])) return false;
        }
        return true;
    };

    std::size_t remaining = count;
    std::size_t i = 0;
    std::size_t sinceLastClip = 0;
    while (remaining > 3) {
        bool clip = isEar(i);
        if (!clip && sinceLastClip >= remaining) {
            // No ear in a full turn: the loop is self-intersecting or
            // degenerate. Clip the first strictly convex vertex, else this one.
            std::size_t j = i;
            do {
                if (strictlyConvex(j)) break;
                j = next[j];
            } while (j != i);
            i = strictlyConvex(j) ? j : i;
            clip = true;
        }
        if (clip) {
            out.push_back({v[prev[i]], v[i], v[next[i]]});
            next[prev[i]] = next[i];
            prev[next[i]] = prev[i];
            i = prev[i];  // the neighbours' status changed; look at them first
            --remaining;
            sinceLastClip = 0;
        } else {
            i = next[i];
            ++sinceLastClip;
        }
    }
    out.push_back({v[prev[i]], v[i], v[next[i]]});
}

}  // namespace strata::geometry::detail
