#include "strata/exact/Crossings.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <utility>

namespace strata::exact {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>;

Point toPoint(const glm::dvec3& p) { return Point(p.x, p.y, p.z); }

bool withoutArea(const std::vector<Point>& p, const Triangle& t) {
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || CGAL::collinear(p[t[0]], p[t[1]], p[t[2]]);
}

// Whether triangles a and b meet beyond the corners they share (the rules
// in the header).
bool meet(const std::vector<Point>& p, const Triangle& a, const Triangle& b) {
    std::array<std::pair<int, int>, 9> shared;
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (a[std::size_t(i)] == b[std::size_t(j)]) shared[std::size_t(count++)] = {i, j};
        }
    }
    const auto corner = [&](const Triangle& t, int k) -> const Point& { return p[t[std::size_t(k % 3)]]; };
    const Kernel::Triangle_3 ta(corner(a, 0), corner(a, 1), corner(a, 2));
    const Kernel::Triangle_3 tb(corner(b, 0), corner(b, 1), corner(b, 2));
    if (count == 0) return CGAL::do_intersect(ta, tb);
    if (count == 1) {
        const auto [i, j] = shared[0];
        const Kernel::Segment_3 farA(corner(a, i + 1), corner(a, i + 2));
        const Kernel::Segment_3 farB(corner(b, j + 1), corner(b, j + 2));
        return CGAL::do_intersect(farA, tb) || CGAL::do_intersect(farB, ta);
    }
    if (count == 2) {
        const Point& s = corner(a, shared[0].first);
        const Point& e = corner(a, shared[1].first);
        const Point& c = corner(a, 3 - shared[0].first - shared[1].first);
        const Point& d = corner(b, 3 - shared[0].second - shared[1].second);
        if (CGAL::orientation(s, e, c, d) != CGAL::COPLANAR) return false;
        return CGAL::coplanar_orientation(s, e, c, d) == CGAL::POSITIVE;
    }
    return true;
}

}  // namespace

std::vector<std::array<std::uint32_t, 2>> crossingTriangles(const mesh::Mesh& mesh) {
    std::vector<Point> points;
    points.reserve(mesh.positions.size());
    for (const glm::dvec3& q : mesh.positions) points.push_back(toPoint(q));
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
    std::vector<Box> boxes;
    boxes.reserve(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const Triangle& t = mesh.triangles[i];
        if (withoutArea(points, t)) continue;
        boxes.emplace_back(points[t[0]].bbox() + points[t[1]].bbox() + points[t[2]].bbox(), std::uint32_t(i));
    }
    std::vector<std::array<std::uint32_t, 2>> pairs;
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        if (!meet(points, mesh.triangles[x.info()], mesh.triangles[y.info()])) return;
        pairs.push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())});
    });
    return pairs;
}

}  // namespace strata::exact
