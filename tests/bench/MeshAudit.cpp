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
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

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

// Whether two triangles meet beyond what they share: no common corner, any
// contact; one common corner, the far edge of either meeting the other; a
// common edge, the far corners folded onto one side of it in one plane.
bool meet(const std::vector<Point>& p, const Triangle& a, const Triangle& b) {
    std::vector<std::pair<int, int>> shared;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a[static_cast<std::size_t>(i)] == b[static_cast<std::size_t>(j)]) shared.emplace_back(i, j);
    const Kernel::Triangle_3 ta(p[a[0]], p[a[1]], p[a[2]]), tb(p[b[0]], p[b[1]], p[b[2]]);
    if (shared.empty()) return CGAL::do_intersect(ta, tb);
    if (shared.size() == 1) {
        const auto [i, j] = shared.front();
        const Kernel::Segment_3 farA(p[a[static_cast<std::size_t>((i + 1) % 3)]], p[a[static_cast<std::size_t>((i + 2) % 3)]]);
        const Kernel::Segment_3 farB(p[b[static_cast<std::size_t>((j + 1) % 3)]], p[b[static_cast<std::size_t>((j + 2) % 3)]]);
        return CGAL::do_intersect(farA, tb) || CGAL::do_intersect(farB, ta);
    }
    if (shared.size() == 2) {
        const int i = 3 - shared[0].first - shared[1].first, j = 3 - shared[0].second - shared[1].second;
        const Point& s = p[a[static_cast<std::size_t>(shared[0].first)]];
        const Point& e = p[a[static_cast<std::size_t>(shared[1].first)]];
        const Point& c = p[a[static_cast<std::size_t>(i)]];
        const Point& d = p[b[static_cast<std::size_t>(j)]];
        if (CGAL::orientation(s, e, c, d) != CGAL::COPLANAR) return false;
        return CGAL::coplanar_orientation(s, e, c, d) == CGAL::POSITIVE;
    }
    return true;  // the same three corners twice
}

void countSelfIntersections(const std::vector<Point>& p, const std::vector<Triangle>& triangles,
                            const std::vector<bool>& skip, Audit& audit) {
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        if (skip[i]) continue;
        const Triangle& t = triangles[i];
        boxes.emplace_back(p[t[0]].bbox() + p[t[1]].bbox() + p[t[2]].bbox(), i);
    }
    CGAL::box_self_intersection_d<CGAL::Parallel_if_available_tag>(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        if (!meet(p, triangles[x.info()], triangles[y.info()])) return;
        if (++audit.selfIntersections <= 5 && std::getenv("STRATA_MESH_AUDIT_WHERE")) {
            for (const std::size_t t : {x.info(), y.info()}) {
                std::fprintf(stderr, "%s", t == x.info() ? "crossing: " : "     and: ");
                for (const std::size_t v : triangles[t]) std::fprintf(stderr, "(%.17g %.17g %.17g) ", p[v].x(), p[v].y(), p[v].z());
                std::fprintf(stderr, "\n");
            }
        }
    });
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
    countSelfIntersections(points, triangles, degenerate, out);
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
