// strata_mesh_audit FILE...: what a slicer would find wrong with an exported
// mesh, measured on the file as written (CGAL's readers, not strata's).
//
// Vertices at one position are one vertex, as STL readers weld them. Per file,
// one line of JSON:
//   triangles, vertices     after welding
//   degenerate              triangles of zero area (a repeated vertex, or three
//                           corners exactly on one line)
//   boundary_edges          edges used by one triangle
//   nonmanifold_edges       edges used by more than two triangles
//   misoriented_edges       edges whose two triangles run them the same way
//   self_intersections      pairs of triangles that meet other than along
//                           the edge or at the corner they share (exact
//                           predicates on the written coordinates)
//   clean                   all of those zero
// STRATA_MESH_AUDIT_WHERE=1 in the environment prints the first few
// crossing pairs on stderr.
// Exit status: 0 when every file is clean, 1 otherwise, 2 on a file that
// cannot be read.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "strata/exact/Crossings.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

struct Audit {
    std::size_t triangles = 0, vertices = 0, degenerate = 0;
    std::size_t boundary = 0, nonManifold = 0, misoriented = 0, selfIntersections = 0;
    bool clean() const {
        return degenerate == 0 && boundary == 0 && nonManifold == 0 && misoriented == 0 && selfIntersections == 0;
    }
};

// Welds points at one position into the first of them.
void weld(std::vector<Point>& points, std::vector<Triangle>& triangles) {
    std::map<Point, std::size_t> first;
    std::vector<std::size_t> to(points.size());
    std::vector<Point> kept;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto [it, added] = first.emplace(points[i], kept.size());
        if (added) kept.push_back(points[i]);
        to[i] = it->second;
    }
    for (Triangle& t : triangles)
        for (std::size_t& v : t) v = to[v];
    points = std::move(kept);
}

bool isDegenerate(const std::vector<Point>& p, const Triangle& t) {
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || CGAL::collinear(p[t[0]], p[t[1]], p[t[2]]);
}

void countEdges(const std::vector<Triangle>& triangles, const std::vector<bool>& skip, Audit& audit) {
    // Per undirected edge: triangles running it low->high and high->low.
    std::unordered_map<std::uint64_t, std::array<int, 2>> uses;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        if (skip[i]) continue;
        for (int k = 0; k < 3; ++k) {
            const std::size_t a = triangles[i][static_cast<std::size_t>(k)], b = triangles[i][static_cast<std::size_t>((k + 1) % 3)];
            const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            ++uses[key][a < b ? 0 : 1];
        }
    }
    for (const auto& [key, n] : uses) {
        const int total = n[0] + n[1];
        if (total == 1) ++audit.boundary;
        else if (total > 2) ++audit.nonManifold;
        else if (n[0] != 1) ++audit.misoriented;
    }
}

void countSelfIntersections(const std::vector<Point>& p, const std::vector<Triangle>& triangles, Audit& audit) {
    strata::mesh::Mesh mesh;
    mesh.positions.reserve(p.size());
    for (const Point& q : p) mesh.positions.emplace_back(q.x(), q.y(), q.z());
    mesh.triangles.reserve(triangles.size());
    for (const Triangle& t : triangles) {
        mesh.triangles.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
    }
    const auto pairs = strata::exact::crossingTriangles(mesh);
    audit.selfIntersections = pairs.size();
    if (!std::getenv("STRATA_MESH_AUDIT_WHERE")) return;
    for (std::size_t i = 0; i < pairs.size() && i < 5; ++i) {
        for (const std::uint32_t t : pairs[i]) {
            std::fprintf(stderr, "%s", t == pairs[i][0] ? "crossing: " : "     and: ");
            for (const std::size_t v : triangles[t]) std::fprintf(stderr, "(%.17g %.17g %.17g) ", p[v].x(), p[v].y(), p[v].z());
            std::fprintf(stderr, "\n");
        }
    }
}

bool audit(const char* path, Audit& out) {
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    if (!CGAL::IO::read_polygon_soup(path, points, polygons) || polygons.empty()) return false;
    std::vector<Triangle> triangles;
    for (const auto& polygon : polygons) {
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k) triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
    weld(points, triangles);
    out.triangles = triangles.size();
    out.vertices = points.size();
    std::vector<bool> degenerate(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        degenerate[i] = isDegenerate(points, triangles[i]);
        if (degenerate[i]) ++out.degenerate;
    }
    countEdges(triangles, degenerate, out);
    countSelfIntersections(points, triangles, out);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: strata_mesh_audit FILE...\n");
        return 2;
    }
    bool allClean = true;
    for (int i = 1; i < argc; ++i) {
        Audit a;
        if (!audit(argv[i], a)) {
            std::fprintf(stderr, "strata_mesh_audit: cannot read a mesh from %s\n", argv[i]);
            return 2;
        }
        std::printf("{\"file\": \"%s\", \"triangles\": %zu, \"vertices\": %zu, \"degenerate\": %zu, "
                    "\"boundary_edges\": %zu, \"nonmanifold_edges\": %zu, \"misoriented_edges\": %zu, "
                    "\"self_intersections\": %zu, \"clean\": %s}\n",
                    argv[i], a.triangles, a.vertices, a.degenerate, a.boundary, a.nonManifold, a.misoriented,
                    a.selfIntersections, a.clean() ? "true" : "false");
        allClean = allClean && a.clean();
    }
    return allClean ? 0 : 1;
}
