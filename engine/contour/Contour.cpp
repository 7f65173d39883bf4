#include "strata/contour/Contour.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "CellTopology.h"
#include "ContourStats.h"
#include "DexelImage.h"
#include "Parallel.h"
#include "FlatRegions.h"
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

// A triangle on a plane that faces against it with at least this shape
// (below) is folded over, not a sliver along an edge.
constexpr double kTurnedShape = 1e-3;

// Twice a triangle's area over its longest edge squared: 0 for a degenerate
// triangle, about 0.87 for an equilateral one. A diagonal whose thinner
// triangle is below this is chosen only when the other is thinner still.
constexpr double kMinTriangleShape = 1e-6;

// Where the mesh crosses itself, the vertices within this many cells of a
// crossing go to their crossings' means, one round after another, the
// reach growing while crossings remain; the last round moves every vertex,
// which leaves the contour of crossings' means, merged only where means lie
// on one plane (no real model of the set has crossed itself so; none
// needed more than three rounds).
constexpr std::array<double, 5> kUntangleReach{1.0, 2.0, 4.0, 8.0, std::numeric_limits<double>::infinity()};

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// A point lies on a leaf's plane when it is this close to it, in cells:
// above the samplers' error (the GPU's depths are single floats, about
// 3e-5 of a cell at 512 cells), far below a cell.
constexpr double kOnPlane = 1e-4;

// A crossing is matched with the plane it lies on this far from it, in
// cells: a few of the GPU's crossings (two in ten thousand on the logo)
// lie off their plane by up to a hundredth of a cell. Where the vertex
// then moves onto the plane, it moves by no more than that.
constexpr double kCrossingOnPlane = 1e-2;

// A crossing farther than this from the plane it matched (in cells) is
// moved onto it before the QEF: the GPU's, whose depths are floats; the
// reference's lie on their planes to a double's rounding and stay.
constexpr double kOffPlane = 1e-7;

// Planes are met only where they are this far from parallel: for two, the
// squared sine of their angle (about 0.06 degrees); for three or more, the
// determinant of the sum of their normals' outer products (three unit
// normals' determinant squared).
constexpr double kLeastPlaneDeterminant = 1e-6;

int planeCount(const VertexPlanes& ids) {
    int n = 0;
    while (n < kMostPlanes && ids[std::size_t(n)] >= 0) ++n;
    return n;
}

// The point on every plane of `ids` nearest `near`; false where they are
// too close to parallel to meet reliably, or (four or more) do not pass
// within `tolerance` of one point.
bool meetPlanes(const PlaneTable& table, const VertexPlanes& ids, const glm::dvec3& near, double tolerance,
                glm::dvec3& out) {
    const int count = planeCount(ids);
    const Plane& a = table[ids[0]];
    if (count == 1) {
        out = near - a.normal * (glm::dot(a.normal, near) - a.offset);
        return true;
    }
    if (count == 2) {
        const Plane& b = table[ids[1]];
        const double g = glm::dot(a.normal, b.normal);
        const double det = 1.0 - g * g;
        if (!(det > kLeastPlaneDeterminant)) return false;
        const double ra = a.offset - glm::dot(a.normal, near);
        const double rb = b.offset - glm::dot(b.normal, near);
        out = near + a.normal * ((ra - g * rb) / det) + b.normal * ((rb - g * ra) / det);
        return true;
    }
    // Least squares about `near`: (sum n nᵀ) d = sum n (offset - n · near).
    glm::dmat3 m(0.0);
    glm::dvec3 rhs(0.0);
    for (int i = 0; i < count; ++i) {
        const Plane& p = table[ids[std::size_t(i)]];
        m += glm::outerProduct(p.normal, p.normal);
        rhs += p.normal * (p.offset - glm::dot(p.normal, near));
    }
    const double det = glm::determinant(m);
    if (!(std::abs(det) > kLeastPlaneDeterminant * kLeastPlaneDeterminant)) return false;
    out = near + glm::inverse(m) * rhs;
    for (int i = 0; i < count; ++i) {
        const Plane& p = table[ids[std::size_t(i)]];
        if (!(std::abs(glm::dot(p.normal, out) - p.offset) <= tolerance)) return false;
    }
    return true;
}

// Adds `id` to `ids` (holding `count`) unless there; false when full.
bool addPlane(VertexPlanes& ids, int& count, std::int32_t id) {
    if (std::find(ids.begin(), ids.begin() + count, id) != ids.begin() + count) return true;
    if (count == kMostPlanes) return false;
    ids[std::size_t(count++)] = id;
    return true;
}

// In increasing order, -1 after them (insertion sort: at most six).
void sortPlanes(VertexPlanes& ids, int count) {
    for (int i = 1; i < count; ++i) {
        for (int j = i; j > 0 && ids[std::size_t(j)] < ids[std::size_t(j - 1)]; --j)
            std::swap(ids[std::size_t(j)], ids[std::size_t(j - 1)]);
    }
}

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
    const double longest = longestEdgeSquared(a, b, c);
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
    // With `planes`, each patch whose crossings' planes meet in the cell
    // puts its vertex there and records them (vertexPlanes; snapToPlanes).
    Contourer(DexelImage& image, ContourStats& stats, const PlaneTable* planes);
    // Contours the whole image (and, with planes, unfolds what snapping
    // folded): the mesh is then mesh(), its vertices' planes vertexPlanes().
    void run();
    const mesh::Mesh& mesh() const { return mesh_; }
    mesh::Mesh takeMesh() { return std::move(mesh_); }
    const std::vector<VertexPlanes>& vertexPlanes() const { return vertexPlanes_; }
    // Puts back, with no planes, the vertices of every quad that snapping
    // turned over or flattened; returns how many moved. With `moved` (a
    // flag per vertex), only the quads of those vertices are split again
    // and looked at.
    std::size_t unfold(std::vector<std::uint8_t> moved = {});
    // Sends every vertex within `reachInCells` of a box in `tangles` to its
    // crossings' mean, off its planes, and unfolds around them; returns how
    // many moved.
    std::size_t untangle(const std::vector<mesh::Bounds>& tangles, double reachInCells);
    glm::dvec3 sharedPlaneNormal(const std::array<std::uint32_t, 3>& t) const;

private:
    std::size_t cellSlot(int i, int j) const { return std::size_t(i) + std::size_t(j) * std::size_t(cells_.x); }
    std::uint8_t configAt(const glm::ivec3& cell) const;
    void computeConfigs(int slab);
    void computeFlips(int slab);
    void placeVertices(int slab);
    std::size_t placeCellVertices(const glm::ivec3& cell, std::uint8_t config, std::uint8_t flips, std::size_t at,
                                  std::size_t& clamped);
    glm::dvec3 keptInCell(const glm::ivec3& cell, glm::dvec3 p, double margin, std::size_t& clamped) const;
    VertexPlanes snapToPlanes(const glm::ivec3& cell, std::span<const std::int32_t> planes, glm::dvec3& point,
                              bool& reached) const;
    // The plane each of a patch's crossings lies on (PlaneTable ids, -1 for
    // none), a crossing named across a ridge moved to the facet it is on.
    void findPlanes(std::span<const HermiteSample> patch, std::span<std::int32_t> found) const;
    VertexPlanes meetPatchPlanes(const glm::ivec3& cell, std::span<const std::int32_t> planes, glm::dvec3& point,
                                 bool& reached) const;
    // The cell's box less `marginInCells` of a cell on every side (grown
    // for a negative margin): its low and high corners.
    std::pair<glm::dvec3, glm::dvec3> cellBox(const glm::ivec3& cell, double marginInCells) const;
    bool withinCell(const glm::ivec3& cell, const glm::dvec3& p, double marginInCells) const;
    bool alongEdgeInCell(const glm::ivec3& cell, const PlaneTable& table, const VertexPlanes& ids,
                         glm::dvec3& point) const;
    void emitQuads(int slab);
    std::size_t emitQuad(const glm::ivec3& vertex, int axis, bool lowInside, std::size_t at);
    std::uint32_t vertexOf(const glm::ivec3& cell, int edge) const;
    void addQuad(const std::array<std::uint32_t, 4>& q, std::size_t at);

    DexelImage& image_;
    ContourStats& stats_;
    const PlaneTable* faces_;  // the solid's planes, or null
    std::vector<VertexPlanes> vertexPlanes_;
    std::vector<glm::dvec3> unsnapped_;  // each vertex where the QEF put it
    std::vector<glm::dvec3> massPoint_;  // each vertex's crossings' mean
    std::vector<std::uint8_t> reached_;  // snapped to a corner outside its cell
    glm::ivec3 vertices_;  // grid vertices per axis
    glm::ivec3 cells_;     // cells per axis
    std::array<std::vector<std::uint8_t>, kPlaneRing> planes_;
    std::array<std::vector<std::uint8_t>, kConfigRing> configs_;
    std::array<std::vector<std::uint8_t>, kVertexRing> flips_;
    std::array<std::vector<std::uint32_t>, kVertexRing> firstVertex_;
    std::vector<std::size_t> rowCount_;  // per row of a slab: its vertices or quads, then where they start
    mesh::Mesh mesh_;
};

Contourer::Contourer(DexelImage& image, ContourStats& stats, const PlaneTable* planes)
    : image_(image), stats_(stats), faces_(planes), vertices_(image.grid().count), cells_(image.grid().count - 1) {
    const std::size_t slabCells = std::size_t(cells_.x) * std::size_t(cells_.y);
    for (auto& c : configs_) c.assign(slabCells, 0);
    for (auto& f : flips_) f.assign(slabCells, 0);
    for (auto& v : firstVertex_) v.assign(slabCells, kNoVertex);
    rowCount_.assign(std::size_t(std::max(cells_.y, 0)), 0);
}

void Contourer::run() {
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
    if (faces_ != nullptr) stats_.unsnappedVertices += unfold();
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
    if (faces_ != nullptr) {
        vertexPlanes_.resize(at, kNoPlanes);
        unsnapped_.resize(at);
        massPoint_.resize(at);
        reached_.resize(at);
    }
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
    std::array<int, kCellEdges> axisOf;  // each of the patch's crossings' grid edge's axis
    for (int p = 0; p < patches.count; ++p) {
        std::size_t n = 0;
        for (int e = 0; e < kCellEdges; ++e) {
            if (patches.patchOfEdge[e] != p) continue;
            axisOf[n] = edgeAxis(e);
            patch[n++] = samples[e];
        }
        // With planes, each crossing first finds the leaf plane it lies on
        // and takes that plane's normal into the QEF (the sampler's own is
        // rounded, or at a ridge the next facet's), and a point off it by
        // more than a double's rounding (the GPU's depths are floats) is
        // moved along its grid edge onto it.
        std::array<std::int32_t, kCellEdges> found;
        found.fill(-1);
        if (faces_ != nullptr) {
            const std::span<const HermiteSample> crossings(patch.data(), n);
            findPlanes(crossings, std::span(found.data(), n));
            for (std::size_t i = 0; i < n; ++i) {
                if (found[i] < 0) continue;
                const Plane& plane = (*faces_)[found[i]];
                patch[i].normal = plane.normal;
                // Along its grid edge, where the plane crosses it.
                const double off = glm::dot(plane.normal, patch[i].point) - plane.offset;
                const double along = plane.normal[axisOf[i]];
                if (std::abs(off) > kOffPlane * image_.grid().spacing && std::abs(along) > 1e-3) {
                    patch[i].point[axisOf[i]] -= off / along;
                }
            }
        }
        const QefSolution qef = minimizeQef(std::span(patch.data(), n));
        const double tolerance = kFeatureResidual * image_.grid().spacing;
        const bool proven = std::size_t(qef.rank) < n && qef.residual <= tolerance * tolerance * double(n);
        glm::dvec3 point = keptInCell(cell, qef.point, proven ? -kFeatureReach : kInteriorMargin, clamped);
        if (faces_ != nullptr) {
            glm::dvec3 mass(0.0);
            for (std::size_t i = 0; i < n; ++i) mass += patch[i].point;
            massPoint_[at] = mass / double(n);
            unsnapped_[at] = point;
            bool reached = false;
            vertexPlanes_[at] = snapToPlanes(cell, std::span(found.data(), n), point, reached);
            reached_[at] = reached ? 1 : 0;
        }
        mesh_.positions[at++] = point;
    }
    return at;
}

// The vertex of a patch on the planes of its crossings: where all of them
// meet, if that is inside the cell and on the leaves' faces (meetPatchPlanes),
// else only those it lies on already.
VertexPlanes Contourer::snapToPlanes(const glm::ivec3& cell, std::span<const std::int32_t> planes,
                                     glm::dvec3& point, bool& reached) const {
    const double tolerance = kOnPlane * image_.grid().spacing;
    const VertexPlanes met = meetPatchPlanes(cell, planes, point, reached);
    if (met[0] >= 0) return met;
    VertexPlanes ids = kNoPlanes;
    int count = 0;
    for (const std::int32_t id : planes) {
        if (id < 0) continue;
        const Plane& plane = (*faces_)[id];
        if (!(std::abs(glm::dot(plane.normal, point) - plane.offset) <= tolerance)) continue;
        if (!addPlane(ids, count, id)) return kNoPlanes;
    }
    if (count == 0) return kNoPlanes;
    sortPlanes(ids, count);
    glm::dvec3 snapped;
    if (!meetPlanes(*faces_, ids, point, tolerance, snapped) || !(glm::length(snapped - point) <= 2.0 * tolerance))
        return kNoPlanes;
    point = snapped;
    return ids;
}

// Each crossing's plane: the one its normal and point name (PlaneTable::find).
// A crossing near a ridge between two facets of a leaf (a curved primitive's
// facets, say) may name the facet across the ridge: the GPU's rasterizer
// decides which triangle covers a ray passing within a fraction of a pixel
// of their shared edge, and the depth then lies on that triangle's plane,
// extended a hair past its edge, where the reference names the facet the
// point is on. A crossing that its plane's triangles do not hold takes
// instead the plane of another of the patch's crossings that passes as near
// it and holds it, or else the plane across the nearest edge of its own
// plane's triangles, if that one holds it.
void Contourer::findPlanes(std::span<const HermiteSample> patch, std::span<std::int32_t> found) const {
    const double tolerance = kOnPlane * image_.grid().spacing;
    const double reach = kCrossingOnPlane * image_.grid().spacing;
    for (std::size_t i = 0; i < patch.size(); ++i) found[i] = faces_->find(patch[i].point, patch[i].normal, reach);
    for (std::size_t i = 0; i < patch.size(); ++i) {
        if (found[i] < 0 || faces_->onTriangle(found[i], patch[i].point, tolerance)) continue;
        std::int32_t holding = -1;
        for (std::size_t j = 0; j < patch.size() && holding < 0; ++j) {
            const std::int32_t other = found[j];
            if (other < 0 || other == found[i]) continue;
            const Plane& plane = (*faces_)[other];
            // Not the other side of a thin wall: a face that meets this one
            // at an edge of the solid, however sharp (down to 60 degrees).
            if (glm::dot(plane.normal, patch[i].normal) < -0.5) continue;
            if (!(std::abs(glm::dot(plane.normal, patch[i].point) - plane.offset) <= reach)) continue;
            if (faces_->onTriangle(other, patch[i].point, tolerance)) holding = other;
        }
        // No crossing of the patch lies on the facet it is on: the leaf
        // triangle across the nearest edge of its own plane's.
        if (holding < 0) holding = faces_->acrossEdge(found[i], patch[i].point, reach, tolerance);
        if (holding >= 0) found[i] = holding;
    }
}

// Where the planes of all of a patch's crossings meet (one to six of them;
// four or more only where they pass through one point, as the faces around
// a vertex of a ball do), moved there from `point` when that is inside the
// cell (an edge's point strictly, by kInteriorMargin; a corner within
// kFeatureReach, as a proven QEF corner may be) and on a leaf triangle of
// each plane: planes that meet where no face of the solid is (a face
// between them gave no crossing) are not the patch's edge or corner, and
// moving there would fold the mesh. `reached`: the point is outside the cell.
VertexPlanes Contourer::meetPatchPlanes(const glm::ivec3& cell, std::span<const std::int32_t> planes,
                                        glm::dvec3& point, bool& reached) const {
    VertexPlanes ids = kNoPlanes;
    int count = 0;
    const double tolerance = kOnPlane * image_.grid().spacing;
    for (const std::int32_t id : planes) {
        if (id < 0 || !addPlane(ids, count, id)) return kNoPlanes;
    }
    sortPlanes(ids, count);
    glm::dvec3 snapped;
    if (!meetPlanes(*faces_, ids, point, tolerance, snapped)) return kNoPlanes;
    // An edge's line may pass through the cell away from the point nearest
    // `point`: the nearest of its points inside the cell.
    if (count == 2 && !alongEdgeInCell(cell, *faces_, ids, snapped)) return kNoPlanes;
    // A corner may lie in the next cell, as a proven QEF corner may.
    const double margin = count == 1 ? 0.0 : count == 2 ? kInteriorMargin : -kFeatureReach;
    if (!withinCell(cell, snapped, margin)) return kNoPlanes;
    for (int i = 0; i < count; ++i) {
        if (!faces_->onTriangle(ids[std::size_t(i)], snapped, tolerance)) return kNoPlanes;
    }
    reached = !withinCell(cell, snapped, kInteriorMargin);
    point = snapped;
    return ids;
}

// The normal, facing as the crossings said, of a plane that one corner of
// `t` was snapped to and all three lie on (to within kOnPlane), or zero.
glm::dvec3 Contourer::sharedPlaneNormal(const std::array<std::uint32_t, 3>& t) const {
    const double tolerance = kOnPlane * image_.grid().spacing;
    for (const std::uint32_t v : t) {
        for (const std::int32_t id : vertexPlanes_[v]) {
            if (id < 0) break;
            const Plane& plane = (*faces_)[id];
            const auto on = [&](std::uint32_t w) {
                return std::abs(glm::dot(plane.normal, mesh_.positions[w]) - plane.offset) <= tolerance;
            };
            if (on(t[0]) && on(t[1]) && on(t[2])) return plane.normal;
        }
    }
    return glm::dvec3(0.0);
}

// Snapping moves a vertex within its cell (a corner a little beyond), and
// a vertex near a cell face can then pass its neighbour's across it: a
// triangle turns over (against its quad's facing before snapping, or
// against a plane its corners lie on) or flattens (two corners met). Such
// a quad's snapped vertices go back to their QEF points (those snapped
// outside their cells first), its diagonal is chosen again, and so on
// until no triangle is turned. Where the QEF points themselves lie turned
// over within a plane (the contour's own fold along a slanted edge), they
// go to their crossings' means. Each vertex moves at most twice.
std::size_t Contourer::unfold(std::vector<std::uint8_t> moved) {
    std::size_t reverted = 0;
    const auto& p = mesh_.positions;
    const auto& q = unsnapped_;
    // The vertices moved by the pass before: only their quads are looked at
    // again (the first pass looks at all, as they were split, unless told
    // which moved).
    const bool all = moved.empty();
    if (all) moved.assign(p.size(), 0);
    std::vector<std::uint8_t> movedNow(p.size(), 0);
    for (bool first = all, changed = true; changed; first = false) {
        changed = false;
        for (std::size_t at = 0; at < mesh_.triangles.size(); at += 2) {
            // The quad's corners, whichever diagonal split it (addQuad).
            const auto& t0 = mesh_.triangles[at];
            const auto& t1 = mesh_.triangles[at + 1];
            const std::array<std::uint32_t, 4> quad =
                t1[0] == t0[0] ? std::array{t0[0], t0[1], t0[2], t1[2]} : std::array{t0[0], t0[1], t1[1], t1[2]};
            if (!first) {
                if (!(moved[quad[0]] | moved[quad[1]] | moved[quad[2]] | moved[quad[3]])) continue;
                addQuad(quad, at);
            }
            // The quad's facing before snapping: its vector area, which
            // does not depend on the diagonal.
            const glm::dvec3 before = glm::cross(q[quad[2]] - q[quad[0]], q[quad[3]] - q[quad[1]]);
            for (const std::size_t f : {at, at + 1}) {
                const auto& t = mesh_.triangles[f];
                const glm::dvec3 now = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
                // Turned within a plane, by more than a sliver along an
                // edge (whose normal says nothing) can be; flattened below
                // triangleShape's least.
                const double longest = longestEdgeSquared(p[t[0]], p[t[1]], p[t[2]]);
                const bool turnedInPlane = glm::dot(now, sharedPlaneNormal(t)) < -kTurnedShape * longest;
                const bool turned = turnedInPlane || glm::dot(now, before) <= 0.0;
                const bool flattened = !(longest > 0.0) || glm::length(now) / longest < kMinTriangleShape;
                if (!turned && !flattened) continue;
                // Corners snapped outside their cells first (one may have
                // met another cell's corner), then every snapped corner.
                bool anyReached = false;
                for (const std::uint32_t v : quad) anyReached = anyReached || reached_[v] != 0;
                bool unsnappedAny = false;
                for (const std::uint32_t v : quad) {
                    if (mesh_.positions[v] == unsnapped_[v] || (anyReached && reached_[v] == 0)) continue;
                    mesh_.positions[v] = unsnapped_[v];
                    vertexPlanes_[v] = kNoPlanes;
                    reached_[v] = 0;
                    movedNow[v] = 1;
                    unsnappedAny = true;
                    ++reverted;
                }
                // The QEF's own points fold here: their crossings' means.
                for (const std::uint32_t v : quad) {
                    if (unsnappedAny || !turnedInPlane || mesh_.positions[v] == massPoint_[v]) continue;
                    mesh_.positions[v] = unsnapped_[v] = massPoint_[v];
                    vertexPlanes_[v] = kNoPlanes;
                    movedNow[v] = 1;
                    ++reverted;
                }
            }
        }
        for (std::size_t v = 0; v < moved.size(); ++v) {
            changed = changed || movedNow[v] != 0;
            moved[v] = movedNow[v];
            movedNow[v] = 0;
        }
    }
    return reverted;
}

std::size_t Contourer::untangle(const std::vector<mesh::Bounds>& tangles, double reachInCells) {
    // The boxes grown by the reach, filed by the buckets of kBucket cells
    // they cover, so that each vertex looks only at the boxes near it.
    constexpr int kBucket = 16;
    const DexelGrid& grid = image_.grid();
    const double reach = reachInCells * grid.spacing;
    const auto bucketOf = [&](const glm::dvec3& p) {
        const glm::dvec3 cell = (p - grid.origin) / grid.spacing;
        return glm::ivec3(glm::floor(cell / double(kBucket)));
    };
    const auto key = [](const glm::ivec3& b) {
        return (std::uint64_t(std::uint32_t(b.x) & 0x1fffff) << 42) | (std::uint64_t(std::uint32_t(b.y) & 0x1fffff) << 21) |
               std::uint64_t(std::uint32_t(b.z) & 0x1fffff);
    };
    std::vector<mesh::Bounds> grown;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets;
    for (const mesh::Bounds& box : std::isfinite(reach) ? tangles : std::vector<mesh::Bounds>{}) {
        mesh::Bounds g;
        g.min = box.min - glm::dvec3(reach);
        g.max = box.max + glm::dvec3(reach);
        const glm::ivec3 low = bucketOf(g.min), high = bucketOf(g.max);
        for (int x = low.x; x <= high.x; ++x)
            for (int y = low.y; y <= high.y; ++y)
                for (int z = low.z; z <= high.z; ++z) buckets[key({x, y, z})].push_back(std::uint32_t(grown.size()));
        grown.push_back(g);
    }
    std::vector<std::uint8_t> moved(mesh_.positions.size(), 0);
    std::size_t count = 0;
    const bool everywhere = !std::isfinite(reach);
    for (std::size_t v = 0; v < mesh_.positions.size(); ++v) {
        glm::dvec3& p = mesh_.positions[v];
        if (p == massPoint_[v]) continue;
        if (!everywhere) {
            const auto found = buckets.find(key(bucketOf(p)));
            if (found == buckets.end()) continue;
            const auto near = [&](std::uint32_t b) {
                const mesh::Bounds& g = grown[b];
                return p.x >= g.min.x && p.y >= g.min.y && p.z >= g.min.z && p.x <= g.max.x && p.y <= g.max.y &&
                       p.z <= g.max.z;
            };
            if (std::none_of(found->second.begin(), found->second.end(), near)) continue;
        }
        p = unsnapped_[v] = massPoint_[v];
        vertexPlanes_[v] = kNoPlanes;
        reached_[v] = 0;
        moved[v] = 1;
        ++count;
    }
    if (count > 0) stats_.unsnappedVertices += unfold(std::move(moved));
    return count;
}

// Moves `point`, on the line where planes ids[0] and ids[1] meet, along it
// into the cell (by kInteriorMargin); false where the line misses the cell.
bool Contourer::alongEdgeInCell(const glm::ivec3& cell, const PlaneTable& table, const VertexPlanes& ids,
                                glm::dvec3& point) const {
    const glm::dvec3 direction = glm::cross(table[ids[0]].normal, table[ids[1]].normal);
    const auto [cellLow, cellHigh] = cellBox(cell, kInteriorMargin);
    double low = -1e300, high = 1e300;
    for (int a = 0; a < 3; ++a) {
        const double from = cellLow[a] - point[a];
        const double to = cellHigh[a] - point[a];
        if (direction[a] == 0.0) {
            if (from > 0.0 || to < 0.0) return false;
            continue;
        }
        const double t0 = from / direction[a], t1 = to / direction[a];
        low = std::max(low, std::min(t0, t1));
        high = std::min(high, std::max(t0, t1));
    }
    if (!(low <= high)) return false;
    point += direction * std::clamp(0.0, low, high);
    return true;
}

bool Contourer::withinCell(const glm::ivec3& cell, const glm::dvec3& p, double marginInCells) const {
    const auto [low, high] = cellBox(cell, marginInCells);
    for (int a = 0; a < 3; ++a) {
        if (!(p[a] >= low[a] && p[a] <= high[a])) return false;
    }
    return true;
}

std::pair<glm::dvec3, glm::dvec3> Contourer::cellBox(const glm::ivec3& cell, double marginInCells) const {
    const double margin = marginInCells * image_.grid().spacing;
    glm::dvec3 low, high;
    for (int a = 0; a < 3; ++a) {
        low[a] = image_.coordinate(a, cell[a]) + margin;
        high[a] = image_.coordinate(a, cell[a] + 1) - margin;
    }
    return {low, high};
}

// A minimizer outside the allowed box (the cell less the margin, or grown by
// kFeatureReach for a proven feature) is clamped to it, not replaced by the
// mass point: a sharp corner just across a cell face stays next to where it
// belongs, on the cell's face, instead of jumping back into the middle.
glm::dvec3 Contourer::keptInCell(const glm::ivec3& cell, glm::dvec3 p, double marginInCells,
                                 std::size_t& clampedCount) const {
    const auto [low, high] = cellBox(cell, marginInCells);
    bool clamped = false;
    for (int a = 0; a < 3; ++a) {
        const double kept = std::isfinite(p[a]) ? std::clamp(p[a], low[a], high[a]) : 0.5 * (low[a] + high[a]);
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

mesh::Mesh contourCounting(const Dexels& dexels, ContourStats& stats, const PlaneTable* planes,
                           const FindTangles& findTangles) {
    DexelImage image(dexels);
    if (image.empty()) return {};
    Contourer contourer(image, stats, planes);
    contourer.run();
    if (planes == nullptr) return contourer.takeMesh();
    if (!findTangles) return mergeFlatRegions(contourer.mesh(), contourer.vertexPlanes(), *planes, stats);
    const std::size_t mergedBefore = stats.mergedVertices;
    for (std::size_t round = 0;; ++round) {
        stats.mergedVertices = mergedBefore;
        mesh::Mesh merged = mergeFlatRegions(contourer.mesh(), contourer.vertexPlanes(), *planes, stats);
        const std::vector<mesh::Bounds> tangles = findTangles(merged);
        if (round == 0) stats.tangles = tangles.size();
        stats.tanglesLeft = tangles.size();
        if (tangles.empty() || round == kUntangleReach.size()) return merged;
        stats.untangledVertices += contourer.untangle(tangles, kUntangleReach[round]);
        ++stats.untangleRounds;
    }
}

mesh::Mesh contour(const Dexels& dexels, const PlaneTable* planes, const FindTangles& findTangles) {
    ContourStats stats;
    return contourCounting(dexels, stats, planes, findTangles);
}

}  // namespace strata::contour
