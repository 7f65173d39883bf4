#include "PolygonTriangulation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace strata::mesh::detail {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// p inside or on the boundary of the counter-clockwise triangle (a, b, c).
bool inClosedTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0;
}

// Whether every corner lies in the plane of the Newell normal `n` through the
// loop's centroid, to within rounding of the coordinates.
bool isPlanar(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& v, const glm::dvec3& n) {
    const double len = glm::length(n);
    if (!(len > 0.0)) return true;  // degenerate: nothing to crease
    glm::dvec3 centre(0.0), lo = positions[v[0]], hi = positions[v[0]];
    for (uint32_t i : v) {
        centre += positions[i];
        lo = glm::min(lo, positions[i]);
        hi = glm::max(hi, positions[i]);
    }
    centre /= double(v.size());
    const double tolerance = 1e-12 * std::max({glm::length(hi - lo), glm::length(lo), glm::length(hi)});
    for (uint32_t i : v)
        if (std::abs(glm::dot(positions[i] - centre, n)) / len > tolerance) return false;
    return true;
}

// The corners of a loop of `count` as a ring: each one's next and previous.
void ringLinks(std::size_t count, std::vector<std::size_t>& next, std::vector<std::size_t>& prev) {
    next.resize(count);
    prev.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        next[i] = (i + 1) % count;
        prev[i] = (i + count - 1) % count;
    }
}

// The triangle of corners a, b, c of a loop, as indices.
void appendTriangle(std::vector<std::array<uint32_t, 3>>& tris, std::size_t a, std::size_t b, std::size_t c) {
    tris.push_back({static_cast<uint32_t>(a), static_cast<uint32_t>(b), static_cast<uint32_t>(c)});
}

// Ear clipping of the counter-clockwise 2D loop `p`; appends triangles of
// positions in `p` (0-based) to `tris`.
void earClip(const std::vector<glm::dvec2>& p, std::vector<std::array<uint32_t, 3>>& tris) {
    const std::size_t count = p.size();
    std::vector<std::size_t> next, prev;
    ringLinks(count, next, prev);
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
            appendTriangle(tris, prev[i], i, next[i]);
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
    appendTriangle(tris, prev[i], i, next[i]);
}

// The plane a face is tessellated in, chosen as OpenSCAD's tessellator
// (libtess2) chooses it: the normal of the largest triangle spanned by the two
// vertices furthest apart along one axis, and the coordinate plane across that
// normal's longest axis. Returns the dropped axis.
int libtessDroppedAxis(const std::vector<glm::vec3>& q) {
    glm::vec3 lo = q[0], hi = q[0];
    std::size_t loAt[3] = {0, 0, 0}, hiAt[3] = {0, 0, 0};
    for (std::size_t i = 0; i < q.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            if (q[i][k] < lo[k]) { lo[k] = q[i][k]; loAt[k] = i; }
            if (q[i][k] > hi[k]) { hi[k] = q[i][k]; hiAt[k] = i; }
        }
    }
    int k = 0;
    if (hi[1] - lo[1] > hi[0] - lo[0]) k = 1;
    if (hi[2] - lo[2] > hi[k] - lo[k]) k = 2;
    glm::vec3 n(0.0f, 0.0f, 1.0f);
    if (lo[k] < hi[k]) {
        const glm::vec3 d1 = q[loAt[k]] - q[hiAt[k]];
        float best = 0.0f;
        for (const glm::vec3& v : q) {
            const glm::vec3 c = glm::cross(d1, v - q[hiAt[k]]);
            const float len2 = glm::dot(c, c);
            if (len2 > best) { best = len2; n = c; }
        }
        if (best <= 0.0f) return 2;  // collinear: any plane will do
    }
    int axis = 0;
    if (std::abs(n[1]) > std::abs(n[0])) axis = 1;
    if (std::abs(n[2]) > std::abs(n[axis])) axis = 2;
    return axis;
}

// Triangulates a convex counter-clockwise loop as libtess2 does a monotone
// region: from the rightmost vertex (by s, then t), cutting triangles off the
// upper or the lower chain, whichever reaches further left.
void monotoneTriangles(const std::vector<glm::dvec2>& p, std::vector<std::array<uint32_t, 3>>& tris) {
    const std::size_t count = p.size();
    std::vector<std::size_t> next, prev;
    ringLinks(count, next, prev);
    auto leq = [&](std::size_t a, std::size_t b) { return p[a].x < p[b].x || (p[a].x == p[b].x && p[a].y <= p[b].y); };
    auto edgeSign = [&](std::size_t u, std::size_t v, std::size_t w) {
        const double gapL = p[v].x - p[u].x, gapR = p[w].x - p[v].x;
        return gapL + gapR > 0.0 ? (p[v].y - p[w].y) * gapL + (p[v].y - p[u].y) * gapR : 0.0;
    };
    auto cutAfter = [&](std::size_t a) {  // cuts off the triangle (a, next a, next next a)
        const std::size_t b = next[a], c = next[b];
        appendTriangle(tris, a, b, c);
        next[a] = c;
        prev[c] = a;
    };
    // An edge is named by its origin; its destination is next[origin].
    std::size_t up = 0;
    for (std::size_t guard = 0; guard < count && leq(next[up], up); ++guard) up = prev[up];
    for (std::size_t guard = 0; guard < count && leq(up, next[up]); ++guard) up = next[up];
    std::size_t lo = prev[up];
    for (std::size_t guard = 0; next[up] != lo && guard < 4 * count; ++guard) {
        if (leq(next[up], lo)) {
            while (next[lo] != up && (leq(next[next[lo]], next[lo]) || edgeSign(lo, next[lo], next[next[lo]]) <= 0.0))
                cutAfter(lo);
            lo = prev[lo];
        } else {
            while (next[lo] != up && (leq(prev[up], up) || edgeSign(next[up], up, prev[up]) >= 0.0)) {
                const std::size_t before = prev[up];
                cutAfter(before);
                up = before;
            }
            up = next[up];
        }
    }
    while (next[next[lo]] != up && next[lo] != up) cutAfter(lo);
    if (next[next[next[lo]]] == lo) appendTriangle(tris, lo, next[lo], next[next[lo]]);
}

double angleAt(const glm::dvec2& apex, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 u = a - apex, w = b - apex;
    const double den = glm::length(u) * glm::length(w);
    const double c = den > 0.0 ? glm::dot(u, w) / den : glm::dot(u, w);
    return std::acos(std::clamp(c, -1.0, 1.0));
}

// Flips inner edges until each is locally Delaunay by libtess2's test: the
// two angles facing an edge sum to less than pi + 0.01.
void delaunayFlips(const std::vector<glm::dvec2>& p, std::vector<std::array<uint32_t, 3>>& tris) {
    const auto key = [](uint32_t a, uint32_t b) { return (static_cast<uint64_t>(a) << 32) | b; };
    std::unordered_map<uint64_t, std::size_t> side;  // directed edge -> triangle on its left
    for (std::size_t t = 0; t < tris.size(); ++t)
        for (int e = 0; e < 3; ++e) side[key(tris[t][e], tris[t][(e + 1) % 3])] = t;
    std::vector<std::pair<uint32_t, uint32_t>> stack;
    std::unordered_set<uint64_t> queued;
    auto push = [&](uint32_t a, uint32_t b) {
        if (!side.count(key(a, b)) || !side.count(key(b, a))) return;  // a boundary edge
        if (queued.count(key(std::min(a, b), std::max(a, b)))) return;
        queued.insert(key(std::min(a, b), std::max(a, b)));
        stack.emplace_back(a, b);
    };
    for (const auto& t : tris)
        for (int e = 0; e < 3; ++e) push(t[e], t[(e + 1) % 3]);
    auto third = [](const std::array<uint32_t, 3>& t, uint32_t a, uint32_t b) {
        for (uint32_t v : t)
            if (v != a && v != b) return v;
        return t[0];
    };
    const double limit = std::numbers::pi + 0.01;
    // Each flip raises the smallest angle of the pair; the bound keeps a
    // degenerate loop from cycling.
    for (std::size_t budget = 64 * tris.size() + 64; !stack.empty() && budget > 0; --budget) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        queued.erase(key(std::min(a, b), std::max(a, b)));
        const std::size_t t1 = side.at(key(a, b)), t2 = side.at(key(b, a));
        const uint32_t c = third(tris[t1], a, b), d = third(tris[t2], a, b);
        if (angleAt(p[c], p[a], p[b]) + angleAt(p[d], p[a], p[b]) < limit) continue;
        // (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
        for (int e = 0; e < 3; ++e) {
            side.erase(key(tris[t1][e], tris[t1][(e + 1) % 3]));
            side.erase(key(tris[t2][e], tris[t2][(e + 1) % 3]));
        }
        tris[t1] = {a, d, c};
        tris[t2] = {d, b, c};
        for (int e = 0; e < 3; ++e) {
            side[key(tris[t1][e], tris[t1][(e + 1) % 3])] = t1;
            side[key(tris[t2][e], tris[t2][(e + 1) % 3])] = t2;
        }
        push(a, d);
        push(d, b);
        push(b, c);
        push(c, a);
    }
}

// Triangulates a face that does not lie in one plane, so that the crease runs
// where OpenSCAD's render puts it: a constrained Delaunay triangulation (with
// libtess2's tolerance) in libtess2's projection of the face, starting from
// libtess2's own triangulation of a convex face, where near-ties keep it.
void triangulateAsOpenScad(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& v,
                           std::vector<std::array<uint32_t, 3>>& out) {
    std::vector<glm::vec3> q(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) q[i] = glm::vec3(positions[v[i]]);
    const int k = libtessDroppedAxis(q);
    const int su = (k + 1) % 3, tu = (k + 2) % 3;
    std::vector<glm::dvec2> p(v.size());
    double area = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        p[i] = {q[i][su], q[i][tu]};
        const glm::vec3& a = q[i];
        const glm::vec3& b = q[(i + 1) % q.size()];
        area += double(a[su]) * b[tu] - double(b[su]) * a[tu];
    }
    // Counter-clockwise in (s, t); clockwise loops are mirrored, which keeps
    // every angle and the triangles' order around each vertex.
    const bool mirrored = area < 0.0;
    if (mirrored)
        for (glm::dvec2& x : p) x.y = -x.y;

    bool convex = true;
    for (std::size_t i = 0; i < p.size() && convex; ++i)
        convex = cross2(p[(i + p.size() - 1) % p.size()], p[i], p[(i + 1) % p.size()]) >= 0.0;
    std::vector<std::array<uint32_t, 3>> tris;
    if (convex) monotoneTriangles(p, tris);
    if (!convex || tris.size() != p.size() - 2) {
        tris.clear();
        earClip(p, tris);
    }
    delaunayFlips(p, tris);
    for (const auto& t : tris) out.push_back({v[t[0]], v[t[1]], v[t[2]]});
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
    if (!isPlanar(positions, v, n)) {
        triangulateAsOpenScad(positions, v, out);
        return;
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
    std::vector<std::array<uint32_t, 3>> tris;
    earClip(p, tris);
    for (const auto& t : tris) out.push_back({v[t[0]], v[t[1]], v[t[2]]});
}

}  // namespace strata::mesh::detail
