// Contouring of tri-dexel images (strata/contour/Contour.h) sampled from
// solids in closed form: the mesh checked by CGAL (closed, 2-manifold,
// outward, no degenerate triangle or self-intersection), its volume against
// the solid's, and the solid's sharp corners and edges found among its
// vertices.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "AnalyticDexels.h"
#include "ContourStats.h"
#include "MeshInspection.h"
#include "strata/contour/Contour.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"

// Inside the room's namespace, where `contour` names the function.
namespace strata::contour::test {
namespace {

constexpr double kPi = std::numbers::pi;

mesh::Mesh contourOf(const Solid& solid, const DexelGrid& grid) { return contour(sample(solid, grid)); }

void expectSound(const MeshInspection& m) { EXPECT_TRUE(m.sound()) << m.describe(); }

double nearestVertex(const mesh::Mesh& mesh, const glm::dvec3& p) {
    double best = 1e300;
    for (const glm::dvec3& v : mesh.positions) best = std::min(best, glm::length(v - p));
    return best;
}

// The vertices within `tolerance` of the segment a–b, as distances from a
// along it, sorted, with both ends added: consecutive values are the gaps.
std::vector<double> alongSegment(const mesh::Mesh& mesh, const glm::dvec3& a, const glm::dvec3& b,
                                 double tolerance) {
    const glm::dvec3 d = glm::normalize(b - a);
    const double length = glm::length(b - a);
    std::vector<double> along{0.0, length};
    for (const glm::dvec3& v : mesh.positions) {
        const double t = glm::dot(v - a, d);
        if (t < 0.0 || t > length) continue;
        if (glm::length(v - (a + t * d)) <= tolerance) along.push_back(t);
    }
    std::sort(along.begin(), along.end());
    return along;
}

double largestGap(const std::vector<double>& sorted) {
    double gap = 0.0;
    for (std::size_t i = 1; i < sorted.size(); ++i) gap = std::max(gap, sorted[i] - sorted[i - 1]);
    return gap;
}

// A box given by its 8 corners (bit a of the index: high side along local
// axis a) and its 6 face planes, for the sharp-feature checks.
struct BoxShape {
    glm::dvec3 center;
    glm::dmat3 axes;
    glm::dvec3 half;
    glm::dvec3 corner(int c) const {
        glm::dvec3 p = center;
        for (int a = 0; a < 3; ++a) p += axes[a] * (((c >> a) & 1) ? half[a] : -half[a]);
        return p;
    }
    // Signed distance for points near the surface (exact on the faces).
    double distance(const glm::dvec3& p) const {
        const glm::dvec3 local = glm::transpose(axes) * (p - center);
        return std::max({std::abs(local.x) - half.x, std::abs(local.y) - half.y, std::abs(local.z) - half.z});
    }
    double volume() const { return 8.0 * half.x * half.y * half.z; }
};

struct SharpFeatures {
    double cornerError = 0.0;     // largest distance of a true corner from its nearest vertex
    double surfaceError = 0.0;    // largest distance of a vertex from the box's surface
    double edgeGap = 0.0;         // largest stretch of a true edge with no vertex on it
    double volumeError = 0.0;     // relative
};

SharpFeatures measureBox(const mesh::Mesh& mesh, const MeshInspection& m, const BoxShape& box, double edgeTol) {
    SharpFeatures s;
    for (int c = 0; c < 8; ++c) s.cornerError = std::max(s.cornerError, nearestVertex(mesh, box.corner(c)));
    for (const glm::dvec3& v : mesh.positions) s.surfaceError = std::max(s.surfaceError, std::abs(box.distance(v)));
    for (int c = 0; c < 8; ++c) {
        for (int a = 0; a < 3; ++a) {
            if ((c >> a) & 1) continue;
            const auto along = alongSegment(mesh, box.corner(c), box.corner(c | (1 << a)), edgeTol);
            s.edgeGap = std::max(s.edgeGap, largestGap(along));
        }
    }
    s.volumeError = std::abs(m.volume - box.volume()) / box.volume();
    return s;
}

}  // namespace

TEST(Contour, AxisAlignedBoxOffTheGridKeepsCornersAndEdgesExactly) {
    const glm::dvec3 low(-0.537, -0.4123, -0.3311), high(0.4619, 0.3777, 0.5213);
    const double h = 0.1;
    const mesh::Mesh mesh = contourOf(*box(low, high), gridAround(low, high, h));
    const MeshInspection m = inspect(mesh);
    expectSound(m);
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.euler(), 2);
    const BoxShape shape{(low + high) * 0.5, glm::dmat3(1.0), (high - low) * 0.5};
    const double size = glm::length(high - low);
    const SharpFeatures s = measureBox(mesh, m, shape, 1e-9 * size);
    EXPECT_LE(s.cornerError, 1e-9 * size);
    EXPECT_LE(s.surfaceError, 1e-9 * size);
    // Every cell an edge passes through has a vertex on it, at the middle of
    // the cell's span along the edge (half a cell more next to a corner).
    EXPECT_LE(s.edgeGap, 1.5 * h + 1e-9);
    EXPECT_LE(s.volumeError, 1e-9);
    std::printf("axis-aligned box: corner %.3g, surface %.3g, edge gap %.3g h, volume %.3g\n", s.cornerError,
                s.surfaceError, s.edgeGap / h, s.volumeError);
}

// A rotated box. Its corners and edges come out exact (to the floats of the
// normals: a tilted plane's normal is off by up to 2^-24 per component, a few
// 1e-8 h at the corner) where the patch that sees the feature's faces has its
// minimizer in its own cell, or proves it by more crossings than planes
// (Contour.cpp, kFeatureReach). A corner cut off by exactly three crossings
// whose planes meet outside the cell is clamped into the cell: DC cannot
// tell it from a small curved cap there, and letting such vertices out folds
// meshes of small balls. So the test counts the exact corners and bounds the
// rest.
TEST(Contour, RotatedBoxKeepsCornersAndEdges) {
    const glm::dvec3 center(0.0123, -0.0311, 0.0217), half(0.41, 0.33, 0.27);
    const glm::dmat3 axes = rotation(0.3, 0.7, 1.1);
    const BoxShape shape{center, axes, half};
    for (double h : {0.1, 0.05}) {
        glm::dvec3 low(1e300), high(-1e300);
        for (int c = 0; c < 8; ++c) low = glm::min(low, shape.corner(c)), high = glm::max(high, shape.corner(c));
        const mesh::Mesh mesh = contourOf(*orientedBox(center, axes, half), gridAround(low, high, h));
        const MeshInspection m = inspect(mesh);
        expectSound(m);
        EXPECT_EQ(m.components, 1u);
        EXPECT_EQ(m.euler(), 2);
        const double floatNormalBound = 1e-6 * h;
        int exactCorners = 0;
        for (int c = 0; c < 8; ++c) exactCorners += nearestVertex(mesh, shape.corner(c)) <= floatNormalBound ? 1 : 0;
        const SharpFeatures s = measureBox(mesh, m, shape, floatNormalBound);
        EXPECT_GE(exactCorners, 6) << "h " << h;
        EXPECT_LE(s.cornerError, 0.1 * h) << "h " << h;
        EXPECT_LE(s.surfaceError, 0.1 * h) << "h " << h;
        EXPECT_LE(s.edgeGap, 2.0 * std::sqrt(3.0) * h) << "h " << h;
        EXPECT_LE(s.volumeError, 1e-5) << "h " << h;
        std::printf("rotated box h %.3g: %d of 8 corners exact, worst %.3g h, surface %.3g h, edge gap %.3g h, "
                    "volume %.3g\n",
                    h, exactCorners, s.cornerError / h, s.surfaceError / h, s.edgeGap / h, s.volumeError);
    }
}

// Dual contouring of a smooth surface: vertices at mass points of crossings
// (or tangent-plane meets) a cell apart, so chords of length about h sit
// inside the surface by about h²/(8R) each way: the volume is off by about
// area × c h² / R with c well below 1. Bound: area × h² / R, and the error at
// h/2 below a third of the error at h (second order).
TEST(Contour, SphereVolumeConvergesAtSecondOrder) {
    const glm::dvec3 center(0.0137, -0.0213, 0.0071);
    const double r = 1.0;
    const double exact = 4.0 / 3.0 * kPi * r * r * r;
    const double area = 4.0 * kPi * r * r;
    double previous = 0.0;
    for (double h : {0.2, 0.1, 0.05, 0.025}) {
        const glm::dvec3 reach(r);
        const mesh::Mesh mesh = contourOf(*sphere(center, r), gridAround(center - reach, center + reach, h));
        const MeshInspection m = inspect(mesh);
        expectSound(m);
        EXPECT_EQ(m.components, 1u);
        EXPECT_EQ(m.euler(), 2);
        const double error = std::abs(m.volume - exact);
        std::printf("sphere h %.3g: volume error %.3g (%.3g of the bound)\n", h, error, error / (area * h * h / r));
        EXPECT_LE(error, area * h * h / r) << "h " << h;
        if (previous > 0.0) {
            EXPECT_LT(error, previous / 3.0) << "h " << h;
        }
        previous = error;
    }
}

namespace {

// The part of a ball of radius r inside a half-space whose plane lies at
// distance d from its center (on the ball's side of the plane: the cap).
double capVolume(double r, double d) {
    const double height = r - d;
    return kPi * height * height * (3.0 * r - height) / 3.0;
}

void expectBoxMinusBall(const glm::dvec3& low, const glm::dvec3& high, const glm::dvec3& ballCenter, double r,
                        double exact, const char* what) {
    const auto solid = subtract(box(low, high), sphere(ballCenter, r));
    // Curved area of the cut plus its rim (where DC bevels the sharp circle
    // by about a cell): the bound is (area / r + rim length) × h².
    double previous = 0.0;
    for (double h : {0.1, 0.05, 0.025}) {
        const mesh::Mesh mesh = contourOf(*solid, gridAround(low, high, h));
        const MeshInspection m = inspect(mesh);
        expectSound(m);
        EXPECT_EQ(m.components, 1u);
        EXPECT_EQ(m.euler(), 2);
        const double error = std::abs(m.volume - exact);
        const double bound = (4.0 * kPi * r * r / r + 2.0 * kPi * r) * h * h;
        std::printf("%s h %.3g: volume error %.3g (%.3g of the bound)\n", what, h, error, error / bound);
        EXPECT_LE(error, bound) << what << " h " << h;
        if (previous > 0.0) {
            EXPECT_LT(error, previous / 2.0) << what << " h " << h;
        }
        previous = error;
    }
}

}  // namespace

TEST(Contour, BoxMinusBallAtACorner) {
    const glm::dvec3 low(-0.5137, -0.4711, -0.4923), high(0.5071, 0.4883, 0.5317);
    const double r = 0.4;
    // An eighth of the ball sits inside the box.
    const double volume = (high.x - low.x) * (high.y - low.y) * (high.z - low.z) - kPi * r * r * r / 6.0;
    expectBoxMinusBall(low, high, high, r, volume, "box minus ball at a corner");
}

TEST(Contour, BoxMinusBallInAFace) {
    const glm::dvec3 low(-0.5137, -0.4711, -0.4923), high(0.5071, 0.4883, 0.5317);
    const double r = 0.35;
    const glm::dvec3 ballCenter(0.0213, -0.0117, high.z + 0.1 * r);
    const double volume = (high.x - low.x) * (high.y - low.y) * (high.z - low.z) - capVolume(r, 0.1 * r);
    expectBoxMinusBall(low, high, ballCenter, r, volume, "box minus ball in a face");
}

TEST(Contour, TorusHasGenusOne) {
    const glm::dvec3 center(0.0173, -0.0119, 0.0231);
    const double major = 0.8, minor = 0.3;
    const glm::dvec3 reach(major + minor, major + minor, minor);
    for (double h : {0.1, 0.05}) {
        const mesh::Mesh mesh = contourOf(*torus(center, major, minor), gridAround(center - reach, center + reach, h));
        const MeshInspection m = inspect(mesh);
        expectSound(m);
        EXPECT_EQ(m.components, 1u);
        EXPECT_EQ(m.euler(), 0);
        const double exact = 2.0 * kPi * kPi * major * minor * minor;
        const double area = 4.0 * kPi * kPi * major * minor;
        const double error = std::abs(m.volume - exact);
        std::printf("torus h %.3g: volume error %.3g (%.3g of area h²/r)\n", h, error, error / (area * h * h / minor));
        EXPECT_LE(error, area * h * h / minor);
    }
}

// Walls two cells thick, their faces off the grid planes (gridAround puts
// the low face 2.37 cells above a plane): each keeps two grid planes of
// inside vertices, so it survives whole, flat faces and sharp
// edges, as one component each.
TEST(Contour, WallsTwoCellsThickSurvive) {
    const double h = 0.1;
    const double thickness = 2.0 * h;
    const glm::dvec3 low(-0.4, -0.5137, -0.4711);
    const glm::dvec3 high(low.x + thickness, 0.4883, 0.5317);
    const double wallVolume = thickness * (high.y - low.y) * (high.z - low.z);
    {
        const mesh::Mesh mesh = contourOf(*box(low, high), gridAround(low, high, h));
        const MeshInspection m = inspect(mesh);
        expectSound(m);
        EXPECT_EQ(m.components, 1u);
        EXPECT_NEAR(m.volume, wallVolume, 1e-9 * wallVolume);
    }
    // Two walls with a gap of two cells between them.
    const glm::dvec3 shift(2.0 * thickness, 0.0, 0.0);
    const auto walls = unite({box(low, high), box(low + shift, high + shift)});
    const mesh::Mesh mesh = contourOf(*walls, gridAround(low, high + shift, h));
    const MeshInspection m = inspect(mesh);
    expectSound(m);
    EXPECT_EQ(m.components, 2u);
    EXPECT_NEAR(m.volume, 2.0 * wallVolume, 2e-9 * wallVolume);
}

namespace {

// Small balls on a coarse grid: centred on random grid vertices (random
// corner signs, every cell configuration) or anywhere (random crossings).
SolidPtr randomBalls(std::mt19937& random, const DexelGrid& grid, bool onVertices) {
    std::uniform_int_distribution<int> index(2, grid.count.x - 3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<SolidPtr> balls;
    const int count = onVertices ? 256 : 8;
    for (int b = 0; b < count; ++b) {
        glm::dvec3 c;
        for (int a = 0; a < 3; ++a) {
            const double i = onVertices ? index(random) : 2.0 + unit(random) * (grid.count[a] - 5);
            c[a] = grid.origin[a] + grid.spacing * i;
        }
        // On vertices: wide enough that balls on neighbouring vertices
        // overlap, so the solid between two inside vertices is inside.
        const double r = grid.spacing * (onVertices ? 0.55 + 0.25 * unit(random) : 0.4 + 1.2 * unit(random));
        balls.push_back(sphere(c, r));
    }
    return unite(std::move(balls));
}

// Winding number of the mesh at p (sum of the triangles' signed solid angles
// over 4π; Van Oosterom and Strackee's formula).
double windingNumber(const mesh::Mesh& mesh, const glm::dvec3& p) {
    double sum = 0.0;
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 a = mesh.positions[t[0]] - p, b = mesh.positions[t[1]] - p, c = mesh.positions[t[2]] - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double numerator = glm::dot(a, glm::cross(b, c));
        const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
        sum += 2.0 * std::atan2(numerator, denominator);
    }
    return sum / (4.0 * kPi);
}

// Whether every component faces the right way, judged by the solid itself:
// the mesh winds once around each grid vertex inside and not at all around
// one outside. Only vertices next to one of the other sign are looked at
// (every component separates some of them), and of those the ones half a
// cell clear of the surface. Unlike CGAL's nesting of
// components, this holds where components cross one another, and for a
// cavity (a gap between balls that a grid vertex sees).
int misorientedVertices(const mesh::Mesh& mesh, const Solid& solid, const DexelGrid& grid) {
    auto at = [&](int i, int j, int k) { return grid.origin + grid.spacing * glm::dvec3(i, j, k); };
    // A vertex nearer the surface than about half a cell may lie on either
    // side of a dual-contoured surface (which cuts chords of small balls):
    // those are left out.
    auto clear = [&](const glm::dvec3& p, bool inside) {
        for (int d = 0; d < 27; ++d) {
            const glm::dvec3 dir(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
            if (d == 13) continue;
            if (solid.contains(p + 0.5 * grid.spacing * glm::normalize(dir)) != inside) return false;
        }
        return true;
    };
    int wrong = 0;
    for (int k = 1; k + 1 < grid.count.z; ++k) {
        for (int j = 1; j + 1 < grid.count.y; ++j) {
            for (int i = 1; i + 1 < grid.count.x; ++i) {
                const bool inside = solid.contains(at(i, j, k));
                const bool boundary = inside != solid.contains(at(i + 1, j, k)) ||
                                      inside != solid.contains(at(i - 1, j, k)) ||
                                      inside != solid.contains(at(i, j + 1, k)) ||
                                      inside != solid.contains(at(i, j - 1, k)) ||
                                      inside != solid.contains(at(i, j, k + 1)) || inside != solid.contains(at(i, j, k - 1));
                if (!boundary || !clear(at(i, j, k), inside)) continue;
                const double w = windingNumber(mesh, at(i, j, k));
                wrong += std::abs(w - (inside ? 1.0 : 0.0)) < 0.5 ? 0 : 1;
            }
        }
    }
    return wrong;
}

}  // namespace

// Where the welding of patch vertices would put four triangles on one edge
// (an ambiguous face whose two segments join the same patches on both
// sides), the face is flipped; this makes sure such faces occur and every
// mesh still comes out closed, 2-manifold and outward. Self-intersections
// are counted, not failed: two blobs a cell apart can cross.
TEST(Contour, RandomBallsOnACoarseGridAreAlwaysManifold) {
    DexelGrid grid;
    grid.origin = {-0.6137, -0.5911, -0.6023};
    grid.spacing = 0.1;
    grid.count = glm::ivec3(12);
    std::mt19937 random(20240607);
    ContourStats total;
    int selfIntersecting = 0;
    constexpr int kTrials = 300;
    for (int trial = 0; trial < kTrials; ++trial) {
        const SolidPtr solid = randomBalls(random, grid, trial % 2 == 0);
        ContourStats stats;
        const mesh::Mesh mesh = contourCounting(sample(*solid, grid), stats);
        total.ambiguousFaces += stats.ambiguousFaces;
        total.flippedFaces += stats.flippedFaces;
        if (mesh.triangles.empty()) continue;
        const MeshInspection m = inspect(mesh);
        selfIntersecting += m.selfIntersects ? 1 : 0;
        ASSERT_TRUE(m.soupIsManifold && m.valid && m.closed && m.degenerate == 0) << "trial " << trial << ":" << m.describe();
        EXPECT_EQ(misorientedVertices(mesh, *solid, grid), 0) << "trial " << trial;
    }
    std::printf("random balls: %zu ambiguous faces, %zu flipped, %d of %d meshes self-intersecting\n",
                total.ambiguousFaces, total.flippedFaces, selfIntersecting, kTrials);
    EXPECT_GT(total.ambiguousFaces, 1000u);
    EXPECT_GT(total.flippedFaces, 0u);
}

namespace {

Dexels twoCrossingBox() {
    const glm::dvec3 low(-0.237, -0.2123, -0.2311), high(0.2619, 0.1777, 0.2213);
    return sample(*box(low, high), gridAround(low, high, 0.1));
}

// The first ray along `axis` that has crossings.
std::size_t firstRayWithCrossings(const Dexels& d, int axis) {
    const auto& first = d.axes[axis].first;
    for (std::size_t r = 0; r + 1 < first.size(); ++r) {
        if (first[r + 1] > first[r]) return r;
    }
    return first.size();
}

}  // namespace

TEST(Contour, BadImagesAreErrors) {
    {
        Dexels d = twoCrossingBox();  // drop one crossing: every later ray shifts by one
        const std::size_t r = firstRayWithCrossings(d, 0);
        auto& rays = d.axes[0];
        rays.crossings.erase(rays.crossings.begin() + rays.first[r]);
        for (std::size_t k = r + 1; k < rays.first.size(); ++k) --rays.first[k];
        EXPECT_THROW(contour(d), Error);
    }
    {
        Dexels d = twoCrossingBox();
        const std::size_t r = firstRayWithCrossings(d, 1);
        auto& c = d.axes[1].crossings;
        std::swap(c[d.axes[1].first[r]].at, c[d.axes[1].first[r] + 1].at);
        EXPECT_THROW(contour(d), Error);
    }
    {
        Dexels d = twoCrossingBox();
        const std::size_t r = firstRayWithCrossings(d, 2);
        d.axes[2].crossings[d.axes[2].first[r]].entering = false;
        EXPECT_THROW(contour(d), Error);
    }
    {
        Dexels d = twoCrossingBox();
        d.axes[0].first.pop_back();
        EXPECT_THROW(contour(d), Error);
    }
}

TEST(Contour, OddCrossingCountMessageNamesTheRay) {
    Dexels d = twoCrossingBox();
    const std::size_t r = firstRayWithCrossings(d, 0);
    auto& rays = d.axes[0];
    rays.crossings.erase(rays.crossings.begin() + rays.first[r] + 1);
    for (std::size_t k = r + 1; k < rays.first.size(); ++k) --rays.first[k];
    try {
        contour(d);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ray " + std::to_string(r) + " along x has 1 crossings"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Contour, EmptyImageGivesAnEmptyMesh) {
    Dexels none;
    EXPECT_TRUE(contour(none).triangles.empty());
    Dexels empty;
    empty.grid.count = glm::ivec3(5);
    EXPECT_TRUE(contour(empty).triangles.empty());
    Dexels sampled = sample(*sphere(glm::dvec3(10.0), 0.1), gridAround(glm::dvec3(0.0), glm::dvec3(1.0), 0.25));
    EXPECT_TRUE(contour(sampled).triangles.empty());
}

namespace {

class SlabCounter : public Progress {
public:
    void update(const char* what, std::size_t done, std::size_t total) override {
        EXPECT_STREQ(what, "contour");
        EXPECT_LE(done, total);
        EXPECT_GE(done, last);
        last = done;
        lastTotal = total;
        ++calls;
    }
    std::size_t last = 0, lastTotal = 0, calls = 0;
};

}  // namespace

TEST(Contour, ReportsProgressPerSlab) {
    const glm::dvec3 low(-0.237, -0.2123, -0.2311), high(0.2619, 0.1777, 0.2213);
    const DexelGrid grid = gridAround(low, high, 0.1);
    const Dexels d = sample(*box(low, high), grid);
    SlabCounter counter;
    {
        ProgressScope scope(&counter);
        contour(d);
    }
    const std::size_t slabs = std::size_t(grid.count.z - 1);
    EXPECT_EQ(counter.lastTotal, slabs);
    EXPECT_EQ(counter.last, slabs);
    EXPECT_EQ(counter.calls, slabs + 1);
}

}  // namespace strata::contour::test
