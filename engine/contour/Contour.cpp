#include "strata/contour/Contour.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "CellTopology.h"
#include "ContourStats.h"
#include "DexelImage.h"
#include "Parallel.h"
#include "Qef.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"

namespace strata::contour {
namespace {

constexpr const char* kProgressWhat = "contour";

// Patch vertices stay this far (in cell sizes) inside their own cell unless
// they are a proven feature (below). Four
// points strictly inside the four cells around a grid edge cannot lie on one
// line, so one of the quad's two diagonals always splits it into triangles of
// non-zero area, and vertices of different cells never coincide (a proven
// feature point may meet another; the diagonal choice then still avoids a
// zero-area triangle where it can). A corner of
// the solid closer than this to a grid plane moves by at most the margin.
constexpr double kInteriorMargin = 1e-6;

// A sharp corner or edge often lies in a cell next to the one whose patch
// sees its faces. Such a minimizer is kept, up to this far (in cells) outside
// its cell, when the crossings prove it: more of them than the rank, all on
// their planes through it to within this fraction of a cell (the planes of a
// box meet in one point; those of a curved surface, sampled four times or
// more, do not, and their meet outside the cell would fold the mesh).
constexpr double kFeatureReach = 1.0;
constexpr double kFeatureResidual = 1e-5;

// Twice a triangle's area over its longest edge squared: 0 for a degenerate
// triangle, about 0.87 for an equilateral one. A diagonal whose thinner
// triangle is below this is chosen only when the other is thinner still.
constexpr double kMinTriangleShape = 1e-6;

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// The four cells around a grid edge along axis a, as offsets in (u, v) from
// the edge's low vertex, counter-clockwise seen from +a (u × v = a).
constexpr std::array<std::array<int, 2>, 4> kCellsAroundEdge{{{-1, -1}, {0, -1}, {0, 0}, {-1, 0}}};

// Slabs of cells are kept in rings: configurations for the slabs below, at
// and above the current one (the flips look across z faces), vertices for
// the current slab and the one below (quads of a z plane join both).
constexpr int kConfigRing = 3;
constexpr int kVertexRing = 2;
constexpr int kPlaneRing = 2;

double triangleShape(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double longest = std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    const double twiceArea = glm::length(glm::cross(b - a, c - a));
    return longest > 0.0 ? twiceArea / longest : 0.0;
}

glm::dvec3 unitNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    return length > 0.0 ? n / length : n;
}

class Contourer {
public:
    Contourer(DexelImage& image, ContourStats& stats);
    mesh::Mesh run();

private:
    std::size_t cellSlot(int i, int j) const { return std::size_t(i) + std::size_t(j) * std::size_t(cells_.x); }
    std::uint8_t configAt(const glm::ivec3& cell) const;
    void computeConfigs(int slab);
    void computeFlips(int slab);
    void placeVertices(int slab);
    std::size_t placeCellVertices(const glm::ivec3& cell, std::uint8_t config, std::uint8_t flips, std::size_t at,
                                  std::size_t& clamped);
    glm::dvec3 keptInCell(const glm::ivec3& cell, glm::dvec3 p, double margin, std::size_t& clamped) const;
    void emitQuads(int slab);
    std::size_t emitQuad(const glm::ivec3& vertex, int axis, bool lowInside, std::size_t at);
    std::uint32_t vertexOf(const glm::ivec3& cell, int edge) const;
    void addQuad(const std::array<std::uint32_t, 4>& q, std::size_t at);

    DexelImage& image_;
    ContourStats& stats_;
    glm::ivec3 vertices_;  // grid vertices per axis
    glm::ivec3 cells_;     // cells per axis
    std::array<std::vector<std::uint8_t>, kPlaneRing> planes_;
    std::array<std::vector<std::uint8_t>, kConfigRing> configs_;
    std::array<std::vector<std::uint8_t>, kVertexRing> flips_;
    std::array<std::vector<std::uint32_t>, kVertexRing> firstVertex_;
    std::vector<std::size_t> rowCount_;  // per row of a slab: its vertices or quads, then where they start
    mesh::Mesh mesh_;
};

Contourer::Contourer(DexelImage& image, ContourStats& stats)
    : image_(image), stats_(stats), vertices_(image.grid().count), cells_(image.grid().count - 1) {
    const std::size_t slabCells = std::size_t(cells_.x) * std::size_t(cells_.y);
    for (auto& c : configs_) c.assign(slabCells, 0);
    for (auto& f : flips_) f.assign(slabCells, 0);
    for (auto& v : firstVertex_) v.assign(slabCells, kNoVertex);
    rowCount_.assign(std::size_t(std::max(cells_.y, 0)), 0);
}

mesh::Mesh Contourer::run() {
    image_.signPlane(0, planes_[0]);
    image_.signPlane(1, planes_[1]);
    computeConfigs(0);
    for (int k = 0; k < cells_.z; ++k) {
        reportProgress(kProgressWhat, std::size_t(k), std::size_t(cells_.z));
        if (k + 1 < cells_.z) {
            image_.signPlane(k + 2, planes_[k % kPlaneRing]);  // plane k is no longer needed
            computeConfigs(k + 1);
        }
        computeFlips(k);
        placeVertices(k);
        emitQuads(k);
    }
    reportProgress(kProgressWhat, std::size_t(cells_.z), std::size_t(cells_.z));
    return std::move(mesh_);
}

// Cells outside the grid hold no surface: all outside.
std::uint8_t Contourer::configAt(const glm::ivec3& cell) const {
    if (cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= cells_.x || cell.y >= cells_.y || cell.z >= cells_.z) {
        return 0;
    }
    return configs_[cell.z % kConfigRing][cellSlot(cell.x, cell.y)];
}

void Contourer::computeConfigs(int slab) {
    const std::vector<std::uint8_t>& low = planes_[slab % kPlaneRing];
    const std::vector<std::uint8_t>& high = planes_[(slab + 1) % kPlaneRing];
    std::vector<std::uint8_t>& configs = configs_[slab % kConfigRing];
    // Corner c of a cell is at offset (c & 1, c >> 1 & 1, c >> 2 & 1)
    // (cornerOffset), written out here: this loop visits every cell.
    const std::size_t row = std::size_t(vertices_.x);
    STRATA_FOR_ROWS
    for (int j = 0; j < cells_.y; ++j) {
        const std::uint8_t* low0 = low.data() + std::size_t(j) * row;
        const std::uint8_t* high0 = high.data() + std::size_t(j) * row;
        for (int i = 0; i < cells_.x; ++i) {
            const std::uint8_t* l = low0 + i;
            const std::uint8_t* h = high0 + i;
            configs[cellSlot(i, j)] = std::uint8_t(l[0] | l[1] << 1 | l[row] << 2 | l[row + 1] << 3 | h[0] << 4 |
                                                   h[1] << 5 | h[row] << 6 | h[row + 1] << 7);
        }
    }
}

// A face is flipped exactly when both its cells would join its two segments
// in one patch (CellTopology.h): the same answer from either side.
void Contourer::computeFlips(int slab) {
    std::vector<std::uint8_t>& flips = flips_[slab % kVertexRing];
    std::size_t ambiguous = 0, flipped = 0;
    STRATA_FOR_ROWS_SUM(ambiguous, flipped)
    for (int j = 0; j < cells_.y; ++j) {
        for (int i = 0; i < cells_.x; ++i) {
            const glm::ivec3 cell(i, j, slab);
            const std::uint8_t config = configAt(cell);
            if (config == 0 || config == 0xff) {  // no surface: nothing to flip
                flips[cellSlot(i, j)] = 0;
                continue;
            }
            const std::uint8_t joined = facesJoinedInOnePatch(config);
            std::uint8_t cellFlips = 0;
            for (int f = 0; f < kCellFaces; ++f) {
                if (((joined >> f) & 1) == 0) continue;
                glm::ivec3 neighbour = cell;
                neighbour[faceAxis(f)] += faceIsHigh(f) ? 1 : -1;
                if ((facesJoinedInOnePatch(configAt(neighbour)) >> faceOpposite(f)) & 1) cellFlips |= 1 << f;
            }
            flips[cellSlot(i, j)] = cellFlips;
            // Each face once: from the cell on its low side.
            for (int f = 1; f < kCellFaces; f += 2) {
                ambiguous += ambiguousFace(config, f) ? 1 : 0;
                flipped += (cellFlips >> f) & 1;
            }
        }
    }
    stats_.ambiguousFaces += ambiguous;
    stats_.flippedFaces += flipped;
}

void Contourer::placeVertices(int slab) {
    std::vector<std::uint32_t>& first = firstVertex_[slab % kVertexRing];
    const std::vector<std::uint8_t>& flips = flips_[slab % kVertexRing];
    // Each row's vertices, then where each row's start.
    STRATA_FOR_ROWS
    for (int j = 0; j < cells_.y; ++j) {
        std::size_t n = 0;
        for (int i = 0; i < cells_.x; ++i) {
            const std::size_t slot = cellSlot(i, j);
            n += std::size_t(cellPatches(configAt({i, j, slab}), flips[slot]).count);
        }
        rowCount_[std::size_t(j)] = n;
    }
    std::size_t at = mesh_.positions.size();
    for (std::size_t j = 0; j < rowCount_.size(); ++j) {
        const std::size_t n = rowCount_[j];
        rowCount_[j] = at;
        at += n;
    }
    if (at >= kNoVertex) throw Error("contour: more vertices than a mesh can index");
    mesh_.positions.resize(at);
    std::size_t clamped = 0;
    STRATA_FOR_ROWS_SUM(clamped)
    for (int j = 0; j < cells_.y; ++j) {
        std::size_t next = rowCount_[std::size_t(j)];
        for (int i = 0; i < cells_.x; ++i) {
            const glm::ivec3 cell(i, j, slab);
            const std::uint8_t config = configAt(cell);
            const std::size_t slot = cellSlot(i, j);
            if (config == 0 || config == 0xff) {
                first[slot] = kNoVertex;
                continue;
            }
            first[slot] = std::uint32_t(next);
            next = placeCellVertices(cell, config, flips[slot], next, clamped);
        }
    }
    stats_.clampedVertices += clamped;
}

// One vertex per patch, in patch order: patch p's vertex is first + p,
// written from `at` on; returns the slot after the last.
std::size_t Contourer::placeCellVertices(const glm::ivec3& cell, std::uint8_t config, std::uint8_t flips,
                                         std::size_t at, std::size_t& clamped) {
    const CellPatches& patches = cellPatches(config, flips);
    std::array<HermiteSample, kCellEdges> samples;
    for (int e = 0; e < kCellEdges; ++e) {
        if (patches.patchOfEdge[e] < 0) continue;
        const glm::ivec3 start = edgeStart(e);
        samples[e] = image_.edgeCrossing(cell + start, edgeAxis(e), ((config >> cornerAt(start)) & 1) != 0);
    }
    std::array<HermiteSample, kCellEdges> patch;
    for (int p = 0; p < patches.count; ++p) {
        std::size_t n = 0;
        for (int e = 0; e < kCellEdges; ++e) {
            if (patches.patchOfEdge[e] == p) patch[n++] = samples[e];
        }
        const QefSolution qef = minimizeQef(std::span(patch.data(), n));
        const double tolerance = kFeatureResidual * image_.grid().spacing;
        const bool proven = std::size_t(qef.rank) < n && qef.residual <= tolerance * tolerance * double(n);
        mesh_.positions[at++] = keptInCell(cell, qef.point, proven ? -kFeatureReach : kInteriorMargin, clamped);
    }
    return at;
}

// A minimizer outside the allowed box (the cell less the margin, or grown by
// kFeatureReach for a proven feature) is clamped to it, not replaced by the
// mass point: a sharp corner just across a cell face stays next to where it
// belongs, on the cell's face, instead of jumping back into the middle.
glm::dvec3 Contourer::keptInCell(const glm::ivec3& cell, glm::dvec3 p, double marginInCells,
                                 std::size_t& clampedCount) const {
    const double margin = marginInCells * image_.grid().spacing;
    bool clamped = false;
    for (int a = 0; a < 3; ++a) {
        const double low = image_.coordinate(a, cell[a]) + margin;
        const double high = image_.coordinate(a, cell[a] + 1) - margin;
        const double kept = std::isfinite(p[a]) ? std::clamp(p[a], low, high) : 0.5 * (low + high);
        clamped = clamped || kept != p[a];
        p[a] = kept;
    }
    clampedCount += clamped ? 1 : 0;
    return p;
}

// The quads of the grid edges whose four cells are all placed by now: the z
// edges of this slab, and the x and y edges of its low plane (between this
// slab and the one below). Edges on the grid's boundary never change sign.
void Contourer::emitQuads(int slab) {
    const std::vector<std::uint8_t>& configs = configs_[slab % kConfigRing];
    auto inside = [](std::uint8_t config, int corner) { return ((config >> corner) & 1) != 0; };
    const int cornerX = cornerAt({1, 0, 0});
    const int cornerY = cornerAt({0, 1, 0});
    const int cornerZ = cornerAt({0, 0, 1});
    // The edges at a cell's low corner that give a quad: bit 2 (z), 0 (x), 1 (y).
    auto edgesOf = [&](int i, int j) {
        const std::uint8_t config = configs[cellSlot(i, j)];
        const bool low = inside(config, 0);
        const bool interiorX = i > 0, interiorY = j > 0, interiorZ = slab > 0;
        int edges = 0;
        if (interiorX && interiorY && low != inside(config, cornerZ)) edges |= 4;
        if (interiorY && interiorZ && low != inside(config, cornerX)) edges |= 1;
        if (interiorX && interiorZ && low != inside(config, cornerY)) edges |= 2;
        return edges;
    };
    STRATA_FOR_ROWS
    for (int j = 0; j < cells_.y; ++j) {
        std::size_t n = 0;
        for (int i = 0; i < cells_.x; ++i) n += std::size_t(std::popcount(unsigned(edgesOf(i, j))));
        rowCount_[std::size_t(j)] = n;
    }
    std::size_t at = mesh_.triangles.size();
    for (std::size_t j = 0; j < rowCount_.size(); ++j) {
        const std::size_t n = rowCount_[j];
        rowCount_[j] = at;
        at += 2 * n;
    }
    mesh_.triangles.resize(at);
    STRATA_FOR_ROWS
    for (int j = 0; j < cells_.y; ++j) {
        std::size_t next = rowCount_[std::size_t(j)];
        for (int i = 0; i < cells_.x; ++i) {
            const int edges = edgesOf(i, j);
            if (edges == 0) continue;
            const bool low = inside(configs[cellSlot(i, j)], 0);
            const glm::ivec3 vertex(i, j, slab);
            if (edges & 4) next = emitQuad(vertex, 2, low, next);
            if (edges & 1) next = emitQuad(vertex, 0, low, next);
            if (edges & 2) next = emitQuad(vertex, 1, low, next);
        }
    }
}

std::size_t Contourer::emitQuad(const glm::ivec3& vertex, int axis, bool lowInside, std::size_t at) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    std::array<std::uint32_t, 4> quad{};
    for (std::size_t n = 0; n < quad.size(); ++n) {
        glm::ivec3 cell = vertex;
        cell[u] += kCellsAroundEdge[n][0];
        cell[v] += kCellsAroundEdge[n][1];
        quad[n] = vertexOf(cell, edgeAt(axis, vertex - cell));
    }
    // Counter-clockwise about +axis faces +axis: outward when the low end is
    // inside, the surface's normal there pointing from inside to outside.
    if (!lowInside) std::reverse(quad.begin(), quad.end());
    addQuad(quad, at);
    return at + 2;
}

std::uint32_t Contourer::vertexOf(const glm::ivec3& cell, int edge) const {
    const std::size_t slot = cellSlot(cell.x, cell.y);
    const int ring = cell.z % kVertexRing;
    const CellPatches& patches = cellPatches(configAt(cell), flips_[ring][slot]);
    return firstVertex_[ring][slot] + std::uint32_t(patches.patchOfEdge[edge]);
}

// Of the two diagonals, the one whose triangles agree best in normal (the
// flatter fold, which follows a sharp edge rather than cutting across it),
// unless it makes a sliver and the other does not.
void Contourer::addQuad(const std::array<std::uint32_t, 4>& q, std::size_t at) {
    const auto& p = mesh_.positions;
    const glm::dvec3 &a = p[q[0]], &b = p[q[1]], &c = p[q[2]], &d = p[q[3]];
    const double shapeAC = std::min(triangleShape(a, b, c), triangleShape(a, c, d));
    const double shapeBD = std::min(triangleShape(a, b, d), triangleShape(b, c, d));
    bool splitAC = shapeAC >= shapeBD;
    if (shapeAC >= kMinTriangleShape && shapeBD >= kMinTriangleShape) {
        const double agreeAC = glm::dot(unitNormal(a, b, c), unitNormal(a, c, d));
        const double agreeBD = glm::dot(unitNormal(a, b, d), unitNormal(b, c, d));
        splitAC = agreeAC >= agreeBD;
    }
    if (splitAC) {
        mesh_.triangles[at] = {q[0], q[1], q[2]};
        mesh_.triangles[at + 1] = {q[0], q[2], q[3]};
    } else {
        mesh_.triangles[at] = {q[0], q[1], q[3]};
        mesh_.triangles[at + 1] = {q[1], q[2], q[3]};
    }
}

}  // namespace

mesh::Mesh contourCounting(const Dexels& dexels, ContourStats& stats) {
    DexelImage image(dexels);
    if (image.empty()) return {};
    return Contourer(image, stats).run();
}

mesh::Mesh contour(const Dexels& dexels) {
    ContourStats stats;
    return contourCounting(dexels, stats);
}

}  // namespace strata::contour
