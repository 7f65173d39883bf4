#include "DexelImage.h"

#include "Parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"

namespace strata::contour {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};

// The three rays through a vertex can disagree about it by rounding where the
// surface passes close by; a vertex is inside when at least two say so.
constexpr int kInsideVotes = 2;

[[noreturn]] void fail(int axis, std::size_t ray, const std::string& what) {
    throw Error("dexel image: ray " + std::to_string(ray) + " along " + kAxisNames[axis] + " " + what);
}

}  // namespace

DexelImage::DexelImage(const Dexels& dexels) : dexels_(dexels) {
    const DexelGrid& g = dexels.grid;
    if (!(g.spacing > 0.0) || !std::isfinite(g.spacing) || !std::isfinite(g.origin.x) ||
        !std::isfinite(g.origin.y) || !std::isfinite(g.origin.z)) {
        throw Error("dexel image: the grid needs a finite origin and a positive spacing");
    }
    if (g.count.x < 2 || g.count.y < 2 || g.count.z < 2) return;  // no cells
    bool anyCrossing = false;
    for (int a = 0; a < 3; ++a) {
        checkRays(a);
        anyCrossing = anyCrossing || !dexels.axes[a].crossings.empty();
    }
    empty_ = !anyCrossing;
    if (!empty_) zCursor_.assign(std::size_t(g.count.x) * std::size_t(g.count.y), 0);
}

std::size_t DexelImage::rayIndex(int axis, int u, int v) const {
    return std::size_t(u) + std::size_t(v) * std::size_t(dexels_.grid.count[(axis + 1) % 3]);
}

// An axis without any crossing may leave `first` empty.
const Crossing* DexelImage::rayBegin(int axis, std::size_t ray) const {
    const DexelRays& rays = dexels_.axes[axis];
    return rays.first.empty() ? nullptr : rays.crossings.data() + rays.first[ray];
}

const Crossing* DexelImage::rayEnd(int axis, std::size_t ray) const {
    const DexelRays& rays = dexels_.axes[axis];
    return rays.first.empty() ? nullptr : rays.crossings.data() + rays.first[ray + 1];
}

void DexelImage::checkRays(int axis) {
    const DexelRays& rays = dexels_.axes[axis];
    const glm::ivec3& count = dexels_.grid.count;
    const std::size_t rayCount = std::size_t(count[(axis + 1) % 3]) * std::size_t(count[(axis + 2) % 3]);
    if (rays.first.empty() && rays.crossings.empty()) return;
    if (rays.first.size() != rayCount + 1 || rays.first.front() != 0 || rays.first.back() != rays.crossings.size()) {
        throw Error(std::string("dexel image: the rays along ") + kAxisNames[axis] + " are not " +
                    std::to_string(rayCount) + " packed lists of the crossings");
    }
    for (std::size_t r = 0; r < rayCount; ++r) {
        if (rays.first[r + 1] < rays.first[r]) fail(axis, r, "ends before it starts");
        const std::size_t n = rays.first[r + 1] - rays.first[r];
        if (n % 2 != 0) fail(axis, r, "has " + std::to_string(n) + " crossings: a ray must end outside the solid");
        const Crossing* c = rayBegin(axis, r);
        for (std::size_t i = 0; i < n; ++i) {
            if (!std::isfinite(c[i].at)) fail(axis, r, "has a crossing at a non-finite place");
            if (i > 0 && c[i].at < c[i - 1].at) {
                fail(axis, r, "lists its crossings out of order (" + std::to_string(c[i].at) + " after " +
                                  std::to_string(c[i - 1].at) + ")");
            }
            // Crossing i enters exactly when the ray is outside before it.
            if (c[i].entering != (i % 2 == 0)) {
                fail(axis, r, "marks crossing " + std::to_string(i) + (c[i].entering ? " entering" : " leaving") +
                                  " where the ray is already " + (i % 2 == 0 ? "outside" : "inside"));
            }
        }
    }
}

// Adds, for every vertex along one ray, whether an odd number of its
// crossings lie at or before the vertex: a crossing exactly at a vertex
// counts before it.
void DexelImage::addParities(int axis, std::size_t ray, int along, int stride, std::vector<std::uint8_t>& votes) const {
    const Crossing* begin = rayBegin(axis, ray);
    const Crossing* end = rayEnd(axis, ray);
    if (begin == end) return;
    const Crossing* c = begin;
    std::size_t slot = std::size_t(along);
    for (int i = 0; i < dexels_.grid.count[axis]; ++i, slot += std::size_t(stride)) {
        const double at = coordinate(axis, i);
        while (c != end && c->at <= at) ++c;
        votes[slot] += std::uint8_t((c - begin) & 1);
    }
}

void DexelImage::signPlane(int k, std::vector<std::uint8_t>& inside) {
    const glm::ivec3& n = dexels_.grid.count;
    if (k != nextPlane_) throw Error("dexel image: sign planes must be read in order");
    ++nextPlane_;
    inside.assign(std::size_t(n.x) * std::size_t(n.y), 0);
    // x rays through (j, k): u = y, v = z. y rays through (k, i): u = z, v = x.
    // Each ray adds to its own row, column or slot: the rays run in parallel
    // (Parallel.h), one direction after the other.
    STRATA_FOR_ROWS
    for (int j = 0; j < n.y; ++j) addParities(0, rayIndex(0, j, k), j * n.x, 1, inside);
    STRATA_FOR_ROWS
    for (int i = 0; i < n.x; ++i) addParities(1, rayIndex(1, k, i), i, n.x, inside);
    const double at = coordinate(2, k);
    const DexelRays& zRays = dexels_.axes[2];
    const std::size_t zCount = zRays.first.empty() ? 0 : zCursor_.size();
    STRATA_FOR_ROWS
    for (std::size_t r = 0; r < zCount; ++r) {
        std::uint32_t& cursor = zCursor_[r];
        const std::uint32_t end = zRays.first[r + 1] - zRays.first[r];
        const Crossing* c = rayBegin(2, r);
        while (cursor < end && c[cursor].at <= at) ++cursor;
        inside[r] += std::uint8_t(cursor & 1);  // z ray r = i + j * count.x: the same slot
    }
    // The grid's outer vertices are outside by contract; holding them so
    // keeps the mesh closed even where a solid touches the grid's box.
    STRATA_FOR_ROWS
    for (int j = 0; j < n.y; ++j) {
        for (int i = 0; i < n.x; ++i) {
            std::uint8_t& s = inside[std::size_t(i) + std::size_t(j) * std::size_t(n.x)];
            const bool outer = i == 0 || j == 0 || k == 0 || i == n.x - 1 || j == n.y - 1 || k == n.z - 1;
            s = !outer && s >= kInsideVotes ? 1 : 0;
        }
    }
}

HermiteSample DexelImage::edgeCrossing(const glm::ivec3& vertex, int axis, bool lowInside) const {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const std::size_t ray = rayIndex(axis, vertex[u], vertex[v]);
    const double low = coordinate(axis, vertex[axis]);
    const double high = coordinate(axis, vertex[axis] + 1);
    // Crossings within (low, high], the half-open span the signs use. Of those
    // that go the way the signs do, the one nearest the inside end: it bounds
    // the solid that inside vertex belongs to, where the others (pairs that
    // the signs do not see) bound a sliver thinner than the edge.
    const Crossing* begin = rayBegin(axis, ray);
    const Crossing* end = rayEnd(axis, ray);
    const Crossing* c = std::upper_bound(begin, end, low, [](double x, const Crossing& k) { return x < k.at; });
    const Crossing* chosen = nullptr;
    for (; c != end && c->at <= high; ++c) {
        if (c->entering == lowInside) continue;
        chosen = c;
        if (lowInside) break;
    }
    HermiteSample sample;
    sample.point[u] = coordinate(u, vertex[u]);
    sample.point[v] = coordinate(v, vertex[v]);
    // The outward normal along the edge, for an edge whose ray disagreed with
    // the signs (they came from the other two rays there).
    glm::dvec3 axisNormal(0.0);
    axisNormal[axis] = lowInside ? 1.0 : -1.0;
    if (chosen == nullptr) {
        sample.point[axis] = 0.5 * (low + high);
        sample.normal = axisNormal;
        return sample;
    }
    sample.point[axis] = chosen->at;
    const glm::dvec3 n(chosen->normal);
    const double length = glm::length(n);
    sample.normal = length > 0.0 && std::isfinite(length) ? n / length : axisNormal;
    return sample;
}

}  // namespace strata::contour
