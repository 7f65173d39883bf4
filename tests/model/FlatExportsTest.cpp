// Extrusions of flat shapes, hulls, Minkowski sums, resizes, projections and
// polyhedra with non-planar faces against OpenSCAD 2021.01's own meshes of the
// same models (tests/data/flat/extrude, hull, resize, projection and
// polyhedron: NAME.scad, its CSG
// export NAME.csg that
// strata reads, and OpenSCAD's mesh NAME.off; scripts/export-openscad-flat.sh
// makes them). OpenSCAD writes six significant digits, so points are matched
// to that precision; the side walls' triangles and a polyhedron's non-planar
// faces (where OpenSCAD's choice of diagonal shapes the surface) must be the
// same triangles, and the solid the same volume.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "../mesh/MeshTestUtil.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using namespace strata::mesh;
using namespace strata::model;

namespace {

const std::string kData = std::string(STRATA_TEST_DIR) + "/data/flat/";

// A model: its folder under tests/data/flat and its name. In `hull/`, the
// hulls' faces may be split any way (Qhull and CGAL choose differently), so
// only the points and the volume are compared there, and the side walls of
// the extrusions among them.
struct Case {
    std::string dir;
    std::string name;
};

// OFF as OpenSCAD writes it: "OFF V F 0", V points, F faces "n i0 i1 ...".
Mesh readOff(const std::string& path) {
    std::ifstream in(path);
    std::string magic;
    std::size_t vertices = 0, faces = 0, edges = 0;
    in >> magic >> vertices >> faces >> edges;
    Mesh mesh;
    mesh.positions.resize(vertices);
    for (auto& p : mesh.positions) in >> p.x >> p.y >> p.z;
    for (std::size_t f = 0; f < faces; ++f) {
        std::size_t n = 0;
        in >> n;
        std::vector<uint32_t> loop(n);
        for (auto& i : loop) in >> i;
        for (std::size_t k = 1; k + 1 < n; ++k) mesh.triangles.push_back({loop[0], loop[k], loop[k + 1]});
    }
    EXPECT_TRUE(in) << path;
    return mesh;
}

// ASCII STL as OpenSCAD writes it, corners that print alike taken as one point.
Mesh readAsciiStl(const std::string& path) {
    std::ifstream in(path);
    Mesh mesh;
    std::map<std::string, uint32_t> points;
    std::array<uint32_t, 3> triangle{};
    int corner = 0;
    for (std::string word; in >> word;) {
        if (word != "vertex") continue;
        std::string x, y, z;
        in >> x >> y >> z;
        const auto [at, added] = points.emplace(x + " " + y + " " + z, static_cast<uint32_t>(mesh.positions.size()));
        if (added) mesh.positions.emplace_back(std::stod(x), std::stod(y), std::stod(z));
        triangle[static_cast<std::size_t>(corner)] = at->second;
        if (++corner == 3) {
            mesh.triangles.push_back(triangle);
            corner = 0;
        }
    }
    EXPECT_FALSE(mesh.triangles.empty()) << path;
    return mesh;
}

// Six significant digits, as OpenSCAD prints.
bool close(double a, double b) { return std::fabs(a - b) <= 6e-6 * std::max(1.0, std::fabs(b)); }
bool close(const glm::dvec3& a, const glm::dvec3& b) { return close(a.x, b.x) && close(a.y, b.y) && close(a.z, b.z); }

// The index of a point of `mesh` that prints as `p`, or -1.
int match(const Mesh& mesh, const glm::dvec3& p) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (close(mesh.positions[i], p)) return static_cast<int>(i);
    return -1;
}

double area(const Mesh& m, const std::array<uint32_t, 3>& t) {
    return 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
}

// The distance from `p` to triangle t of `m` (closest point by regions).
double distanceToTriangle(const Mesh& m, const std::array<uint32_t, 3>& t, const glm::dvec3& p) {
    const glm::dvec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double nn = glm::dot(n, n);
    if (nn > 0.0) {
        // Inside the prism over the triangle: the distance to its plane.
        const glm::dvec3 q = p - n * (glm::dot(p - a, n) / nn);
        const bool inside = glm::dot(glm::cross(b - a, q - a), n) >= 0.0 && glm::dot(glm::cross(c - b, q - b), n) >= 0.0 &&
                            glm::dot(glm::cross(a - c, q - c), n) >= 0.0;
        if (inside) return glm::length(p - q);
    }
    auto toSegment = [&p](const glm::dvec3& u, const glm::dvec3& v) {
        const glm::dvec3 d = v - u;
        const double dd = glm::dot(d, d);
        const double s = dd > 0.0 ? std::clamp(glm::dot(p - u, d) / dd, 0.0, 1.0) : 0.0;
        return glm::length(p - (u + s * d));
    };
    return std::min({toSegment(a, b), toSegment(b, c), toSegment(c, a)});
}

// A cap triangle: flat at one height (linear_extrude), or in a plane through
// the z axis (the ends of a partial rotate_extrude). Caps may be triangulated
// any way; walls may not.
bool isCap(const Mesh& m, const std::array<uint32_t, 3>& t) {
    const glm::dvec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    if (close(a.z, b.z) && close(b.z, c.z)) return true;
    auto cross = [](const glm::dvec3& u, const glm::dvec3& v) { return u.x * v.y - u.y * v.x; };
    const double scale = std::max({glm::length(a), glm::length(b), glm::length(c), 1.0});
    return std::fabs(cross(a, b)) < 1e-5 * scale * scale && std::fabs(cross(b, c)) < 1e-5 * scale * scale &&
           std::fabs(cross(a, c)) < 1e-5 * scale * scale;
}

class FlatExports : public ::testing::TestWithParam<Case> {};

TEST_P(FlatExports, MeshMatchesOpenScad) {
    const std::string name = GetParam().name;
    const std::string base = kData + GetParam().dir + "/" + name;
    // Hull faces may be split any way; so may a resized twist or hull.
    const bool hullFaces = (GetParam().dir != "extrude" && GetParam().dir != "polyhedron" && name.rfind("flat_", 0) != 0) || name.rfind("cut_", 0) == 0 ||
                           name.rfind("shadow_difference", 0) == 0;
    const scene::Tree tree = scene::parseCsgFile(base + ".csg");
    ASSERT_TRUE(tree.warnings.empty()) << tree.warnings.front().message;
    ASSERT_EQ(tree.leaves.size(), 1u);
    const Model model = buildModel(tree);
    const Mesh& ours = model.leafMeshes[0];
    // OpenSCAD's OFF keeps a polyhedron's faces as given; its STL shows how
    // it splits them.
    const Mesh theirs = GetParam().dir == "polyhedron" ? readAsciiStl(base + ".stl") : readOff(base + ".off");

    EXPECT_TRUE(checkMesh(ours).ok()) << checkMesh(ours).describe();
    // A cut's corners where it crosses a face depend on how OpenSCAD's CGAL
    // split that face (a rotated quad is not quite flat), and where two leaves'
    // sections cross, strata's corner lies on Clipper's grid and CGAL's does
    // not: for cuts the region is compared, through the volume, and every
    // corner of ours must lie within a grid step of one of theirs.
    const bool cut = GetParam().dir == "projection" && name.rfind("cut_", 0) == 0;
    // Likewise where a node takes the exact result of a difference or
    // intersection: new corners lie on the other solid's triangles, split one
    // way by CGAL in OpenSCAD and another in strata. The volume says the
    // region is the same.
    const bool exact = GetParam().dir != "extrude" && !cut &&
                       (name.find("difference") != std::string::npos || name.find("intersection") != std::string::npos);
    // Every point of OpenSCAD's mesh is one of ours, and the other way round.
    if (cut) {
        for (const auto& p : ours.positions) {
            double nearest = 1e300;
            for (const auto& q : theirs.positions) nearest = std::min(nearest, glm::length(p - q));
            EXPECT_LT(nearest, 2.0 / 65536) << name << ": ours " << p.x << " " << p.y << " " << p.z;
        }
    }
    for (const auto& p : theirs.positions) {
        if (cut || exact) break;
        EXPECT_GE(match(ours, p), 0) << name << ": theirs " << p.x << " " << p.y << " " << p.z;
    }
    // A minkowski sum of non-convex solids is a union of hulls: where they
    // overlap, CGAL's corefinement keeps corners that OpenSCAD's Nef union
    // merges away, so each of ours need only lie on OpenSCAD's surface.
    const bool union_ = name.rfind("nonconvex_", 0) == 0;
    if (union_) {
        for (const auto& p : ours.positions) {
            double nearest = 1e300;
            for (const auto& t : theirs.triangles) nearest = std::min(nearest, distanceToTriangle(theirs, t, p));
            // Within the six digits OpenSCAD prints of each coordinate.
            const double digits = 1e-5 * std::max({1.0, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
            EXPECT_LT(nearest, digits) << name << ": ours " << p.x << " " << p.y << " " << p.z;
        }
    }
    // (A resized sphere or cone keeps its caps as fans around an added centre
    // point, where OpenSCAD's export keeps the polygon: there only theirs are
    // looked up in ours, and the volume says nothing else was added.)
    if (GetParam().dir != "resize" && !cut && !exact && !union_) {
        for (const auto& p : ours.positions) EXPECT_GE(match(theirs, p), 0) << name << ": ours " << p.x << " " << p.y << " " << p.z;
    }

    // Their wall triangles with area are ours (either way round).
    std::set<std::array<uint32_t, 3>> ourTriangles;
    for (auto t : ours.triangles) {
        std::sort(t.begin(), t.end());
        ourTriangles.insert(t);
    }
    std::size_t walls = 0;
    for (const auto& t : theirs.triangles) {
        if (hullFaces) break;
        if (area(theirs, t) < 1e-9 || isCap(theirs, t)) continue;
        std::array<uint32_t, 3> mapped{};
        for (int k = 0; k < 3; ++k) mapped[static_cast<std::size_t>(k)] = static_cast<uint32_t>(match(ours, theirs.positions[t[static_cast<std::size_t>(k)]]));
        std::sort(mapped.begin(), mapped.end());
        EXPECT_TRUE(ourTriangles.count(mapped)) << name << ": a wall triangle of OpenSCAD's is not ours";
        ++walls;
    }
    EXPECT_TRUE(hullFaces || walls > 0u);
    const double expected = test::signedVolume(theirs);
    EXPECT_NEAR(test::signedVolume(ours), expected, 1e-4 * std::fabs(expected)) << name;
}

std::vector<Case> cases(const std::string& dir) {
    std::vector<Case> all;
    for (const auto& entry : std::filesystem::directory_iterator(kData + dir))
        if (entry.path().extension() == ".scad") all.push_back({dir, entry.path().stem().string()});
    std::sort(all.begin(), all.end(), [](const Case& a, const Case& b) { return a.name < b.name; });
    return all;
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Extrusions, FlatExports, ::testing::ValuesIn(cases("extrude")), caseName);
INSTANTIATE_TEST_SUITE_P(Hulls, FlatExports, ::testing::ValuesIn(cases("hull")), caseName);
INSTANTIATE_TEST_SUITE_P(Resizes, FlatExports, ::testing::ValuesIn(cases("resize")), caseName);
INSTANTIATE_TEST_SUITE_P(Projections, FlatExports, ::testing::ValuesIn(cases("projection")), caseName);
INSTANTIATE_TEST_SUITE_P(NonPlanarPolyhedra, FlatExports, ::testing::ValuesIn(cases("polyhedron")), caseName);

}  // namespace
