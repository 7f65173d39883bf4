// The contour rebuilt on the solid's planes (Contour.h with a PlaneTable):
// boxes and cut boxes sampled in closed form, their planes from meshes
// written here, the result checked by CGAL (MeshInspection) for soundness
// and volume, and held to the few triangles their flat faces need.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "AnalyticDexels.h"
#include "ContourStats.h"
#include "MeshInspection.h"
#include "strata/contour/Contour.h"
#include "strata/contour/Planes.h"
#include "strata/core/Progress.h"
#include "strata/exact/Crossings.h"

namespace strata::contour::test {
namespace {

// A box's 12 triangles, outward: the mesh a leaf would hand the table.
mesh::Mesh boxMesh(const glm::dvec3& center, const glm::dmat3& axes, const glm::dvec3& half) {
    mesh::Mesh m;
    for (int c = 0; c < 8; ++c) {
        glm::dvec3 p = center;
        for (int a = 0; a < 3; ++a) p += axes[a] * (((c >> a) & 1) ? half[a] : -half[a]);
        m.positions.push_back(p);
    }
    // Each face as a quad of corner codes, counter-clockwise from outside.
    const std::array<std::array<std::uint32_t, 4>, 6> faces{{{0, 2, 3, 1},
                                                             {4, 5, 7, 6},
                                                             {0, 1, 5, 4},
                                                             {2, 6, 7, 3},
                                                             {0, 4, 6, 2},
                                                             {1, 3, 7, 5}}};
    for (const auto& q : faces) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
    }
    return m;
}

double boxVolume(const glm::dvec3& half) { return 8.0 * half.x * half.y * half.z; }

using SurfaceMesh = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

SurfaceMesh toSurface(const mesh::Mesh& m) {
    SurfaceMesh s;
    std::vector<SurfaceMesh::Vertex_index> v;
    for (const glm::dvec3& p : m.positions) v.push_back(s.add_vertex({p.x, p.y, p.z}));
    for (const auto& t : m.triangles) s.add_face(v[t[0]], v[t[1]], v[t[2]]);
    return s;
}

// The volume of a − b, by CGAL's corefinement of the two meshes: the exact
// answer the sampled solid should keep.
double differenceVolume(const mesh::Mesh& a, const mesh::Mesh& b) {
    SurfaceMesh sa = toSurface(a), sb = toSurface(b), out;
    EXPECT_TRUE(CGAL::Polygon_mesh_processing::corefine_and_compute_difference(sa, sb, out));
    return CGAL::Polygon_mesh_processing::volume(out);
}

// The volume of the union of `parts`, by CGAL's corefinement.
double unionVolume(const std::vector<mesh::Mesh>& parts) {
    SurfaceMesh all;
    for (const mesh::Mesh& part : parts) {
        SurfaceMesh s = toSurface(part), out;
        EXPECT_TRUE(CGAL::Polygon_mesh_processing::corefine_and_compute_union(all, s, out));
        all = std::move(out);
    }
    return CGAL::Polygon_mesh_processing::volume(all);
}

// A block with a turned slot cut through it, and the two leaves' meshes.
struct SlottedBlock {
    SolidPtr solid;
    std::vector<mesh::Mesh> leaves;
    glm::dvec3 low, high;
};
SlottedBlock slottedBlock() {
    const glm::dvec3 low(-0.537, -0.4123, -0.3311), high(0.4619, 0.3777, 0.5213);
    const glm::dvec3 slotCenter(0.0313, 0.0171, 0.0917), slotHalf(0.9, 0.11, 0.2);
    const glm::dmat3 slotAxes = rotation(0.0, 0.25, 0.6);
    return SlottedBlock{subtract(box(low, high), orientedBox(slotCenter, slotAxes, slotHalf)),
                        {boxMesh((low + high) * 0.5, glm::dmat3(1.0), (high - low) * 0.5),
                         boxMesh(slotCenter, slotAxes, slotHalf)},
                        low,
                        high};
}

struct Rebuilt {
    mesh::Mesh mesh;
    MeshInspection inspection;
    ContourStats stats;
};

// The tangles as the export finds them, here on the mesh in doubles:
// the overlap of each crossing pair's boxes.
std::vector<mesh::Bounds> crossingPlaces(const mesh::Mesh& m) {
    std::vector<mesh::Bounds> places;
    for (const auto& pair : exact::crossingTriangles(m)) {
        mesh::Bounds a, b;
        for (const std::uint32_t v : m.triangles[pair[0]]) a.extend(m.positions[v]);
        for (const std::uint32_t v : m.triangles[pair[1]]) b.extend(m.positions[v]);
        a.min = glm::max(a.min, b.min);
        a.max = glm::min(a.max, b.max);
        places.push_back(a);
    }
    return places;
}

// The contour rebuilt on the leaves' planes as the export asks for it:
// untangled where it crosses itself.
Rebuilt rebuild(const Solid& solid, const DexelGrid& grid, const std::vector<mesh::Mesh>& leaves) {
    const PlaneTable planes = PlaneTable::fromMeshes(leaves);
    Rebuilt r;
    r.mesh = contourCounting(sample(solid, grid), r.stats, &planes, crossingPlaces);
    r.inspection = inspect(r.mesh);
    return r;
}

}  // namespace

TEST(PlaneTable, FindsThePlaneAndFacingACrossingLiesOn) {
    const std::vector<mesh::Mesh> cube{boxMesh(glm::dvec3(0.0), glm::dmat3(1.0), glm::dvec3(1.0))};
    const PlaneTable table = PlaneTable::fromMeshes(cube);
    // Six planes, two triangles each, in both facings.
    EXPECT_EQ(table.size(), 12u);
    const glm::dvec3 onTop(0.3, -0.2, 1.0);
    const std::int32_t up = table.find(onTop, glm::dvec3(0, 0, 1), 1e-6);
    const std::int32_t down = table.find(onTop, glm::dvec3(0, 0, -1), 1e-6);
    ASSERT_GE(up, 0);
    ASSERT_GE(down, 0);
    EXPECT_NE(up, down);
    EXPECT_EQ(table[up].normal, glm::dvec3(0, 0, 1));
    EXPECT_DOUBLE_EQ(table[up].offset, 1.0);
    EXPECT_EQ(table[down].normal, glm::dvec3(0, 0, -1));
    // Off the plane by more than the tolerance, or facing a degree away: none.
    EXPECT_EQ(table.find(onTop + glm::dvec3(0, 0, 2e-6), glm::dvec3(0, 0, 1), 1e-6), -1);
    const double tilt = 1.0 * 3.14159265358979 / 180.0;
    EXPECT_EQ(table.find(onTop, glm::dvec3(std::sin(tilt), 0, std::cos(tilt)), 1e-6), -1);
    // Within the tolerance, and a normal a little off (a float sampler's): found.
    EXPECT_EQ(table.find(onTop + glm::dvec3(0, 0, 5e-7), glm::normalize(glm::dvec3(1e-5, 0, 1)), 1e-6), up);
    // The plane's triangles bound it: a point beyond the cube's face is on
    // its plane but on none of its triangles.
    EXPECT_TRUE(table.onTriangle(up, onTop, 1e-9));
    EXPECT_TRUE(table.onTriangle(down, glm::dvec3(1.0, 1.0, 1.0), 1e-9));
    EXPECT_FALSE(table.onTriangle(up, glm::dvec3(1.5, 0.0, 1.0), 1e-9));
}

// A roof of two facets meeting at a ridge 10 degrees from flat: a point on
// one facet just past the ridge lies within a hair of the other facet's
// plane extended, and that facet's plane names the one across the ridge,
// in the facing it was asked in; away from every edge, none.
TEST(PlaneTable, NamesTheFacetAcrossARidge) {
    mesh::Mesh roof;
    const double rise = std::tan(5.0 * 3.14159265358979 / 180.0);
    roof.positions = {{-1, 0, 0}, {0, 0, rise}, {1, 0, 0}, {-1, 1, 0}, {0, 1, rise}, {1, 1, 0}};
    // Two facets (two triangles each), up-facing, sharing the ridge 1-4;
    // the roof need not be closed for the table.
    roof.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
    const PlaneTable table = PlaneTable::fromMeshes(std::vector<mesh::Mesh>{roof});
    const glm::dvec3 left = glm::normalize(glm::dvec3(-rise, 0, 1)), right = glm::normalize(glm::dvec3(rise, 0, 1));
    const std::int32_t a = table.find(glm::dvec3(-0.5, 0.5, 0.5 * rise), left, 1e-9);
    const std::int32_t b = table.find(glm::dvec3(0.5, 0.5, 0.5 * rise), right, 1e-9);
    ASSERT_GE(a, 0);
    ASSERT_GE(b, 0);
    // On facet a, 10⁻⁴ past the ridge: 2 × 10⁻⁵ off b's plane, on none of b's triangles.
    const glm::dvec3 past(-1e-4, 0.5, rise * (1.0 - 1e-4));
    EXPECT_FALSE(table.onTriangle(b, past, 1e-6));
    EXPECT_EQ(table.acrossEdge(b, past, 1e-4, 1e-6), a);
    EXPECT_EQ(table.acrossEdge(b ^ 1, past, 1e-4, 1e-6), a ^ 1);  // the facings of a subtracted leaf
    EXPECT_EQ(table.acrossEdge(b, past, 1e-6, 1e-6), -1);        // farther from b's plane than the reach
    EXPECT_EQ(table.acrossEdge(b, glm::dvec3(0.5, 0.5, 0.5 * rise + 1e-5), 1e-4, 1e-6), -1);
}

TEST(PlaneTable, TrianglesOnOnePlaneShareIt) {
    // Two cubes side by side: their top faces lie on one plane, as do their
    // bottoms and the far and near sides; the faces between them are one
    // plane in opposite facings.
    const std::vector<mesh::Mesh> cubes{boxMesh(glm::dvec3(0.0), glm::dmat3(1.0), glm::dvec3(1.0)),
                                        boxMesh(glm::dvec3(2.0, 0.0, 0.0), glm::dmat3(1.0), glm::dvec3(1.0))};
    const PlaneTable table = PlaneTable::fromMeshes(cubes);
    // x = -1, x = 1, x = 3, y = ±1, z = ±1: seven planes, both facings.
    EXPECT_EQ(table.size(), 14u);
    const std::int32_t top = table.find(glm::dvec3(2.5, 0.0, 1.0), glm::dvec3(0, 0, 1), 1e-9);
    EXPECT_EQ(table.find(glm::dvec3(-0.5, 0.0, 1.0), glm::dvec3(0, 0, 1), 1e-9), top);
    EXPECT_TRUE(table.onTriangle(top, glm::dvec3(2.5, 0.5, 1.0), 1e-9));
    EXPECT_TRUE(table.onTriangle(top, glm::dvec3(-0.5, 0.5, 1.0), 1e-9));
}

// An axis-aligned box off the grid: every face comes out as the two
// triangles it needs, every vertex a corner of the box.
TEST(FlatRegions, ABoxIsTwelveTriangles) {
    const glm::dvec3 low(-0.537, -0.4123, -0.3311), high(0.4619, 0.3777, 0.5213);
    const glm::dvec3 half = (high - low) * 0.5;
    for (const double h : {0.1, 0.03}) {
        const Rebuilt r =
            rebuild(*box(low, high), gridAround(low, high, h), {boxMesh((low + high) * 0.5, glm::dmat3(1.0), half)});
        EXPECT_TRUE(r.inspection.sound()) << r.inspection.describe();
        EXPECT_EQ(r.inspection.euler(), 2);
        EXPECT_EQ(r.mesh.triangles.size(), 12u) << "h " << h;
        EXPECT_NEAR(r.inspection.volume, boxVolume(half), 1e-12);
        EXPECT_GT(r.stats.mergedVertices, 0u);
    }
}

// Samples as the GPU's result peel gives them: depths in single precision,
// here each moved along its ray by up to 10⁻⁴ of a cell (a deterministic
// scatter; a float's step at 512 cells is about 3 × 10⁻⁵ of one).
Dexels withRoundedDepths(Dexels dexels) {
    std::size_t k = 0;
    for (DexelRays& rays : dexels.axes) {
        for (Crossing& x : rays.crossings) {
            x.at += dexels.grid.spacing * 1e-4 * (double((k++ * 7919) % 2001) / 1000.0 - 1.0);
        }
    }
    return dexels;
}

// The turned box from samples off their planes by a float's rounding: each
// crossing finds its face, moves along its grid edge onto the face's plane
// and takes its normal, so the box comes out as its 12 triangles, as from
// exact samples (taken as they come, the same samples gave 200 and 1,562).
TEST(FlatRegions, SamplesOffTheirPlanesByRoundingGiveTheSameBox) {
    const glm::dvec3 center(0.0123, -0.0311, 0.0217), half(0.41, 0.33, 0.27);
    const glm::dmat3 axes = rotation(0.3, 0.7, 1.1);
    const mesh::Mesh leaf = boxMesh(center, axes, half);
    const mesh::Bounds box = mesh::boundsOf(leaf);
    const PlaneTable planes = PlaneTable::fromMeshes(std::vector<mesh::Mesh>{leaf});
    for (const double h : {0.1, 0.02}) {
        const Dexels rounded = withRoundedDepths(sample(*orientedBox(center, axes, half), gridAround(box.min, box.max, h)));
        const mesh::Mesh m = contour(rounded, &planes, crossingPlaces);
        const MeshInspection inspection = inspect(m);
        EXPECT_TRUE(inspection.sound()) << inspection.describe();
        EXPECT_EQ(m.triangles.size(), 12u) << "h " << h;
        EXPECT_NEAR(inspection.volume, boxVolume(half), 1e-9) << "h " << h;
    }
}

// A box turned by odd angles: its planes are nowhere near the grid's, and
// its corners meet in cells of their own or are clamped into a neighbour.
TEST(FlatRegions, ATurnedBoxKeepsItsVolumeInFewTriangles) {
    const glm::dvec3 center(0.0123, -0.0311, 0.0217), half(0.41, 0.33, 0.27);
    const glm::dmat3 axes = rotation(0.3, 0.7, 1.1);
    glm::dvec3 low(1e300), high(-1e300);
    const mesh::Mesh leaf = boxMesh(center, axes, half);
    for (const glm::dvec3& p : leaf.positions) low = glm::min(low, p), high = glm::max(high, p);
    for (const double h : {0.1, 0.05, 0.02}) {
        const Rebuilt r = rebuild(*orientedBox(center, axes, half), gridAround(low, high, h), {leaf});
        EXPECT_TRUE(r.inspection.sound()) << r.inspection.describe();
        EXPECT_EQ(r.inspection.euler(), 2);
        // The exact box has 12. Where the contour folded a triangle over
        // near a corner (it does at h = 0.05), the triangles around it are
        // left as they are.
        EXPECT_LE(r.mesh.triangles.size(), 48u) << "h " << h;
        EXPECT_NEAR(r.inspection.volume, boxVolume(half), 1e-5 * boxVolume(half)) << "h " << h;
        std::printf("turned box h %.3g: %zu triangles, volume off by %.3g\n", h, r.mesh.triangles.size(),
                    std::abs(r.inspection.volume - boxVolume(half)) / boxVolume(half));
        if (h == 0.02) {
            EXPECT_EQ(r.mesh.triangles.size(), 12u);
        }
    }
}

// A block with a turned slot cut through it: the slot's walls and the
// block's faces meet along edges of every direction, and the cut faces
// face inward (the subtracted leaf's planes in their other facing).
TEST(FlatRegions, ABlockCutByATurnedSlotIsSoundAndSmall) {
    const SlottedBlock block = slottedBlock();
    const DexelGrid grid = gridAround(block.low, block.high, 0.02);
    const Rebuilt r = rebuild(*block.solid, grid, block.leaves);
    EXPECT_TRUE(r.inspection.sound()) << r.inspection.describe();
    const double exact = differenceVolume(block.leaves[0], block.leaves[1]);
    // Within a few cells' volume (two corners of the slot come out where
    // the contour's own points would fold: at their crossings' means).
    EXPECT_NEAR(r.inspection.volume, exact, 4.0 * std::pow(grid.spacing, 3));
    // The same image contoured without the planes has a hundred times the
    // triangles (the exact difference has 40 or so).
    const mesh::Mesh dense = contour(sample(*block.solid, grid));
    EXPECT_LE(100 * r.mesh.triangles.size(), dense.triangles.size());
    std::printf("block with a turned slot: %zu triangles (%zu without the planes), volume off by %.3g\n",
                r.mesh.triangles.size(), dense.triangles.size(), std::abs(r.inspection.volume - exact) / exact);
}

// A box with a ball cut out: the ball has no planes in the table, so its
// surface keeps the contour's triangles, and the box's faces merge up to
// the ball's rim; the two meet without a fold.
TEST(FlatRegions, CurvedSurfacesWithoutPlanesStayAsTheContourMadeThem) {
    const glm::dvec3 low(-0.5137, -0.4711, -0.4923), high(0.5071, 0.4883, 0.5317);
    const SolidPtr solid = subtract(box(low, high), sphere(high, 0.4));
    const DexelGrid grid = gridAround(low, high, 0.05);
    const Rebuilt r = rebuild(*solid, grid, {boxMesh((low + high) * 0.5, glm::dmat3(1.0), (high - low) * 0.5)});
    EXPECT_TRUE(r.inspection.sound()) << r.inspection.describe();
    const mesh::Mesh dense = contour(sample(*solid, grid));
    const MeshInspection plain = inspect(dense, false);
    EXPECT_NEAR(r.inspection.volume, plain.volume, 1e-6 * plain.volume);
    EXPECT_LT(r.mesh.triangles.size(), dense.triangles.size());
}

namespace {

// Turned boxes side by side with gaps of a fraction of a cell to two cells
// between them, and their meshes: where two sheets of the solid lie a cell
// apart, or a sharp edge is seen by few crossings, the rebuilt contour can
// cross itself.
struct BoxRow {
    SolidPtr solid;
    std::vector<mesh::Mesh> leaves;
};
BoxRow boxRow(std::mt19937& random, double spacing) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    BoxRow row;
    std::vector<SolidPtr> parts;
    double x = 0.0;
    for (int b = 0; b < 4; ++b) {
        const glm::dvec3 half(0.05 + 0.1 * unit(random), 0.1 + 0.2 * unit(random), 0.1 + 0.2 * unit(random));
        const glm::dmat3 axes = rotation(0.3 * unit(random), 0.3 * unit(random), 0.3 * unit(random));
        // The box's reach along x, turned: the gap is measured between reaches.
        double reach = 0.0;
        for (int a = 0; a < 3; ++a) reach += std::abs(axes[a].x) * half[a];
        const glm::dvec3 center(x + reach, 0.05 * unit(random), 0.05 * unit(random));
        x = center.x + reach + spacing * 2.0 * unit(random);
        parts.push_back(orientedBox(center, axes, half));
        row.leaves.push_back(boxMesh(center, axes, half));
    }
    row.solid = unite(std::move(parts));
    return row;
}

}  // namespace

// Given a way to find where the mesh crosses itself, the contour moves the
// vertices there to their crossings' means and merges again. Two rows of
// the seeded sequence whose rebuilt mesh crosses itself (about one row in
// thirty does): untangled, each is sound, with no crossing left, and keeps
// the union's exact volume to within the cells around the moved vertices.
TEST(FlatRegions, UntanglesWhereTheRebuiltMeshCrossesItself) {
    constexpr double kSpacing = 0.03;
    constexpr std::array<int, 2> kCrossingRows{5, 24};
    std::mt19937 random(20261130);
    for (int trial = 0; trial <= kCrossingRows.back(); ++trial) {
        const BoxRow row = boxRow(random, kSpacing);
        if (std::find(kCrossingRows.begin(), kCrossingRows.end(), trial) == kCrossingRows.end()) continue;
        mesh::Bounds box;
        for (const mesh::Mesh& leaf : row.leaves) box.extend(mesh::boundsOf(leaf));
        const Dexels dexels = sample(*row.solid, gridAround(box.min, box.max, kSpacing));
        const PlaneTable planes = PlaneTable::fromMeshes(row.leaves);
        ContourStats plain, untangled;
        const mesh::Mesh before = contourCounting(dexels, plain, &planes);
        ASSERT_FALSE(exact::crossingTriangles(before).empty()) << "row " << trial << " no longer crosses itself";
        const mesh::Mesh after = contourCounting(dexels, untangled, &planes, crossingPlaces);
        EXPECT_GT(untangled.tangles, 0u);
        EXPECT_GT(untangled.untangledVertices, 0u);
        EXPECT_EQ(untangled.tanglesLeft, 0u);
        const MeshInspection m = inspect(after);
        ASSERT_TRUE(m.sound()) << "row " << trial << ":" << m.describe();
        const double cell = kSpacing * kSpacing * kSpacing;
        EXPECT_NEAR(m.volume, unionVolume(row.leaves), 0.5 * cell * double(untangled.untangledVertices + 4))
            << "row " << trial;
        // The merge still does its work around them.
        EXPECT_LT(after.triangles.size(), 2 * before.triangles.size());
    }
}

// A finder never satisfied (it names one place, the middle of the block, in
// every answer) takes the contour through every round: the reach grows
// until every vertex sits at its crossings' mean, and what comes back is
// that contour, sound, merged only where such means lie on one plane (a
// flat patch's), so larger than the contour rebuilt on the planes.
TEST(FlatRegions, TheLastRoundLeavesTheContourOfCrossingsMeans) {
    const SlottedBlock block = slottedBlock();
    const Dexels dexels = sample(*block.solid, gridAround(block.low, block.high, 0.04));
    const PlaneTable planes = PlaneTable::fromMeshes(block.leaves);
    int calls = 0;
    const FindTangles never = [&](const mesh::Mesh&) {
        ++calls;
        mesh::Bounds middle;
        middle.extend((block.low + block.high) * 0.5);
        return std::vector<mesh::Bounds>{middle};
    };
    ContourStats stats;
    const mesh::Mesh last = contourCounting(dexels, stats, &planes, never);
    EXPECT_EQ(calls, 6);
    EXPECT_EQ(stats.untangleRounds, 5u);
    EXPECT_EQ(stats.tanglesLeft, 1u);
    const mesh::Mesh rebuilt = contour(dexels, &planes);
    const mesh::Mesh unmerged = contour(dexels);
    EXPECT_GT(last.triangles.size(), 2 * rebuilt.triangles.size());
    EXPECT_LT(last.triangles.size(), unmerged.triangles.size());
    EXPECT_TRUE(inspect(last).sound()) << inspect(last).describe();
}

// Without places to untangle, the mesh is the one the contour always made.
TEST(FlatRegions, AMeshThatDoesNotCrossItselfIsLeftAsItIs) {
    const SlottedBlock block = slottedBlock();
    const Dexels dexels = sample(*block.solid, gridAround(block.low, block.high, 0.02));
    const PlaneTable planes = PlaneTable::fromMeshes(block.leaves);
    ContourStats stats;
    const mesh::Mesh plain = contour(dexels, &planes);
    const mesh::Mesh checked = contourCounting(dexels, stats, &planes, crossingPlaces);
    EXPECT_EQ(stats.tangles, 0u);
    EXPECT_EQ(stats.untangleRounds, 0u);
    EXPECT_EQ(checked.positions, plain.positions);
    EXPECT_EQ(checked.triangles, plain.triangles);
}

}  // namespace strata::contour::test

namespace strata::contour::test {
namespace {

// The merge's progress: vertices removed so far, of the contour's, never
// going back, ending at all of them; and a stop asked for on the way.
class MergeProgress : public Progress {
public:
    void update(const char* what, std::size_t done, std::size_t total) override {
        if (std::string(what) != "contour: flat regions") return;
        EXPECT_LE(done, total);
        EXPECT_GE(done, last);
        last = done;
        lastTotal = total;
        ++calls;
    }
    bool cancelled() const override { return stop && calls > 1; }
    bool stop = false;
    std::size_t last = 0, lastTotal = 0, calls = 0;
};

}  // namespace

TEST(FlatRegions, ReportsProgressPerPassAndStopsWhenAsked) {
    const SlottedBlock block = slottedBlock();
    const Dexels dexels = sample(*block.solid, gridAround(block.low, block.high, 0.02));
    const PlaneTable planes = PlaneTable::fromMeshes(block.leaves);
    MergeProgress progress;
    {
        ProgressScope scope(&progress);
        contour(dexels, &planes);
    }
    EXPECT_GT(progress.calls, 2u);
    EXPECT_GT(progress.lastTotal, 0u);
    EXPECT_EQ(progress.last, progress.lastTotal);
    MergeProgress stopping;
    stopping.stop = true;
    ProgressScope scope(&stopping);
    EXPECT_THROW(contour(dexels, &planes), Cancelled);
}

}  // namespace strata::contour::test

#ifdef _OPENMP
#include <omp.h>

namespace strata::contour::test {

// The merge runs its first passes in slabs on every core: the mesh is the
// same, vertex for vertex, on one thread or several.
TEST(FlatRegions, OneMeshOnAnyNumberOfThreads) {
    const SlottedBlock block = slottedBlock();
    const Dexels dexels = sample(*block.solid, gridAround(block.low, block.high, 0.01));
    const PlaneTable planes = PlaneTable::fromMeshes(block.leaves);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const mesh::Mesh one = contour(dexels, &planes);
    omp_set_num_threads(4);
    const mesh::Mesh four = contour(dexels, &planes);
    omp_set_num_threads(threads);
    EXPECT_EQ(one.positions, four.positions);
    EXPECT_EQ(one.triangles, four.triangles);
    EXPECT_LT(one.triangles.size(), 200u);
}

}  // namespace strata::contour::test
#endif
