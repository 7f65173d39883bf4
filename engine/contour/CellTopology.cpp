#include "CellTopology.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

namespace strata::contour {
namespace {

constexpr int kConfigs = 256;
constexpr int kFlipSets = 1 << kCellFaces;
constexpr int kFaceCorners = 4;

// A face's corners in cyclic order, and its edges: edge k joins corner k to
// corner k + 1.
struct FaceCycle {
    std::array<int, kFaceCorners> corners{};
    std::array<int, kFaceCorners> edges{};
};

FaceCycle faceCycle(int face) {
    const int a = faceAxis(face);
    const int u = (a + 1) % 3;
    const int v = (a + 2) % 3;
    constexpr std::array<std::pair<int, int>, kFaceCorners> kAround{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    std::array<glm::ivec3, kFaceCorners> offsets{};
    FaceCycle cycle;
    for (int k = 0; k < kFaceCorners; ++k) {
        offsets[k][a] = faceIsHigh(face) ? 1 : 0;
        offsets[k][u] = kAround[k].first;
        offsets[k][v] = kAround[k].second;
        cycle.corners[k] = cornerAt(offsets[k]);
    }
    for (int k = 0; k < kFaceCorners; ++k) {
        const glm::ivec3& p = offsets[k];
        const glm::ivec3& q = offsets[(k + 1) % kFaceCorners];
        const int along = p[u] != q[u] ? u : v;
        glm::ivec3 start = p;
        start[along] = std::min(p[along], q[along]);
        cycle.edges[k] = edgeAt(along, start);
    }
    return cycle;
}

const std::array<FaceCycle, kCellFaces>& faceCycles() {
    static const std::array<FaceCycle, kCellFaces> cycles = [] {
        std::array<FaceCycle, kCellFaces> c;
        for (int f = 0; f < kCellFaces; ++f) c[f] = faceCycle(f);
        return c;
    }();
    return cycles;
}

bool inside(std::uint8_t config, int corner) { return ((config >> corner) & 1) != 0; }

// The segments of one face: pairs of its sign-change edges.
std::vector<std::pair<int, int>> faceSegments(std::uint8_t config, int face, bool flipped) {
    const FaceCycle& cycle = faceCycles()[face];
    std::vector<int> changes;
    for (int k = 0; k < kFaceCorners; ++k) {
        if (inside(config, cycle.corners[k]) != inside(config, cycle.corners[(k + 1) % kFaceCorners])) {
            changes.push_back(cycle.edges[k]);
        }
    }
    if (changes.size() == 2) return {{changes[0], changes[1]}};
    if (changes.size() != kFaceCorners) return {};
    // Corner k lies between edges k - 1 and k; cut off the corners of the
    // chosen sign.
    const bool cutInside = !flipped;
    std::vector<std::pair<int, int>> segments;
    for (int k = 0; k < kFaceCorners; ++k) {
        if (inside(config, cycle.corners[k]) == cutInside) {
            segments.emplace_back(cycle.edges[(k + kFaceCorners - 1) % kFaceCorners], cycle.edges[k]);
        }
    }
    return segments;
}

// Union-find over the 12 edges: every cycle of segments becomes one patch.
CellPatches computePatches(std::uint8_t config, std::uint8_t flips) {
    std::array<int, kCellEdges> parent{};
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&parent](int e) {
        while (parent[e] != e) e = parent[e] = parent[parent[e]];
        return e;
    };
    for (int f = 0; f < kCellFaces; ++f) {
        for (const auto& [p, q] : faceSegments(config, f, ((flips >> f) & 1) != 0)) parent[find(p)] = find(q);
    }
    CellPatches patches;
    std::array<int, kCellEdges> patchOfRoot{};
    patchOfRoot.fill(-1);
    for (int e = 0; e < kCellEdges; ++e) {
        patches.patchOfEdge[e] = -1;
        if (!edgeChangesSign(config, e)) continue;
        int& patch = patchOfRoot[find(e)];
        if (patch < 0) patch = patches.count++;
        patches.patchOfEdge[e] = static_cast<std::int8_t>(patch);
    }
    return patches;
}

}  // namespace

glm::ivec3 cornerOffset(int corner) { return {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1}; }

int cornerAt(const glm::ivec3& offset) { return offset.x + 2 * offset.y + 4 * offset.z; }

int edgeAxis(int edge) { return edge / 4; }

glm::ivec3 edgeStart(int edge) {
    const int a = edgeAxis(edge);
    glm::ivec3 start(0);
    start[(a + 1) % 3] = edge & 1;
    start[(a + 2) % 3] = (edge >> 1) & 1;
    return start;
}

int edgeAt(int axis, const glm::ivec3& start) { return axis * 4 + start[(axis + 1) % 3] + 2 * start[(axis + 2) % 3]; }

bool edgeChangesSign(std::uint8_t config, int edge) {
    const glm::ivec3 start = edgeStart(edge);
    glm::ivec3 end = start;
    end[edgeAxis(edge)] = 1;
    return inside(config, cornerAt(start)) != inside(config, cornerAt(end));
}

bool ambiguousFace(std::uint8_t config, int face) {
    const FaceCycle& cycle = faceCycles()[face];
    const bool s0 = inside(config, cycle.corners[0]);
    return s0 == inside(config, cycle.corners[2]) && s0 != inside(config, cycle.corners[1]) &&
           s0 != inside(config, cycle.corners[3]);
}

const CellPatches& cellPatches(std::uint8_t config, std::uint8_t flips) {
    static const std::vector<CellPatches> table = [] {
        std::vector<CellPatches> t(std::size_t(kConfigs) * kFlipSets);
        for (int c = 0; c < kConfigs; ++c) {
            for (int f = 0; f < kFlipSets; ++f) {
                t[std::size_t(c) * kFlipSets + f] = computePatches(std::uint8_t(c), std::uint8_t(f));
            }
        }
        return t;
    }();
    return table[std::size_t(config) * kFlipSets + (flips & (kFlipSets - 1))];
}

bool faceSegmentsInOnePatch(std::uint8_t config, int face, std::uint8_t flips) {
    if (!ambiguousFace(config, face)) return false;
    const auto segments = faceSegments(config, face, ((flips >> face) & 1) != 0);
    const CellPatches& patches = cellPatches(config, flips);
    return patches.patchOfEdge[segments[0].first] == patches.patchOfEdge[segments[1].first];
}

std::uint8_t facesJoinedInOnePatch(std::uint8_t config) {
    static const std::array<std::uint8_t, kConfigs> table = [] {
        std::array<std::uint8_t, kConfigs> t{};
        for (int c = 0; c < kConfigs; ++c) {
            for (int f = 0; f < kCellFaces; ++f) {
                if (faceSegmentsInOnePatch(std::uint8_t(c), f, 0)) t[c] |= std::uint8_t(1 << f);
            }
        }
        return t;
    }();
    return table[config];
}

}  // namespace strata::contour
