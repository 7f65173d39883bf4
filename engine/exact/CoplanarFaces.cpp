#include "CoplanarFaces.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_face_base_2.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "strata/core/Threads.h"

namespace strata::exact::detail {
namespace {

using Kernel = CGAL::Epeck;
using Point = Kernel::Point_3;
using Vertex = ExactSolid::Vertex_index;
using Face = ExactSolid::Face_index;
using Halfedge = ExactSolid::Halfedge_index;
using Triangle = std::array<Vertex, 3>;

// Union-find over faces, by index.
std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

using Sources = ExactSolid::Property_map<Face, std::uint64_t>;

std::atomic<std::uint64_t> nextSource{1};

// Whether the two faces of the edge of `h` lie in one plane and face one
// way: pieces of one leaf triangle do; else the far corners of the two
// triangles lie on opposite sides of the edge in one plane.
bool flatEdge(const ExactSolid& s, Halfedge h, const std::optional<Sources>& sources) {
    const Halfedge o = s.opposite(h);
    if (sources) {
        const std::uint64_t a = (*sources)[s.face(h)];
        if (a != 0 && a == (*sources)[s.face(o)]) return true;
    }
    const Point& p = s.point(s.source(h));
    const Point& q = s.point(s.target(h));
    const Point& r = s.point(s.target(s.next(h)));
    const Point& t = s.point(s.target(s.next(o)));
    // A triangle without area has no plane to share: its edges are creases,
    // and the triangle stays as it is.
    if (CGAL::collinear(p, q, r) || CGAL::collinear(q, p, t)) return false;
    return CGAL::coplanar(p, q, r, t) && CGAL::coplanar_orientation(p, q, r, t) == CGAL::NEGATIVE;
}

// One region's outline as constraints, triangulated in the plane of its
// faces seen along the axis `Traits` drops; triangles inside the outline
// (an odd number of outline crossings from outside) are appended to `out`
// in the orientation of `sample`, one of the region's faces.
template <class Traits>
void triangulateRegion(const ExactSolid& s, const std::vector<std::pair<Vertex, Vertex>>& outline, Face sample,
                       std::vector<Triangle>& out) {
    using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Vertex, Traits>;
    using FaceBase = CGAL::Triangulation_face_base_with_info_2<int, Traits,
                                                               CGAL::Constrained_Delaunay_triangulation_face_base_2<Traits>>;
    using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
    using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

    Cdt cdt;
    auto insert = [&](Vertex v) {
        const typename Cdt::Vertex_handle h = cdt.insert(s.point(v));
        // Two points of the mesh at one position (parts of the result that
        // touch at a corner) cannot both be corners of one triangulation.
        if (h->info() != Vertex() && h->info() != v) throw std::runtime_error("two outline points at one position");
        h->info() = v;
        return h;
    };
    for (const auto& [a, b] : outline) cdt.insert_constraint(insert(a), insert(b));

    // Nesting: 0 outside, one more across each outline edge.
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
    std::deque<std::pair<typename Cdt::Face_handle, int>> todo{{cdt.infinite_face(), 0}};
    while (!todo.empty()) {
        auto [f, level] = todo.front();
        todo.pop_front();
        if (f->info() != -1) continue;
        f->info() = level;
        for (int i = 0; i < 3; ++i) {
            const typename Cdt::Face_handle n = f->neighbor(i);
            if (n->info() != -1) continue;
            if (cdt.is_constrained(typename Cdt::Edge(f, i))) todo.emplace_back(n, level + 1);
            else todo.emplace_front(n, level);
        }
    }

    // The triangulation's faces turn counter-clockwise as Traits sees them.
    const Halfedge h = s.halfedge(sample);
    const bool counterClockwise =
        Traits().orientation_2_object()(s.point(s.source(h)), s.point(s.target(h)), s.point(s.target(s.next(h)))) ==
        CGAL::COUNTERCLOCKWISE;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (f->info() % 2 == 0) continue;
        const Vertex a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
        out.push_back(counterClockwise ? Triangle{a, b, c} : Triangle{a, c, b});
    }
}

// The solid's faces in regions joined across flat edges (flatEdge): each
// edge's flatness, and each face's region as a union-find parent list.
struct Regions {
    std::vector<char> flat;           // by edge index
    std::vector<std::size_t> parent;  // by face index (findRoot)
    bool isFlat(const ExactSolid& s, Halfedge h) const { return flat[s.edge(h).idx()] != 0; }
};

Regions flatRegions(const ExactSolid& s, const std::optional<Sources>& sources) {
    Regions r{std::vector<char>(s.num_edges(), 0), std::vector<std::size_t>(s.num_faces())};
    for (std::size_t i = 0; i < r.parent.size(); ++i) r.parent[i] = i;
    for (auto e : s.edges()) {
        const Halfedge h = s.halfedge(e);
        if (!flatEdge(s, h, sources)) continue;
        r.flat[e.idx()] = 1;
        const std::size_t a = findRoot(r.parent, s.face(h).idx()), b = findRoot(r.parent, s.face(s.opposite(h)).idx());
        if (a != b) r.parent[a] = b;
    }
    return r;
}

// Points to keep: those on three or more creases, or on two that turn, and
// the corners of a triangle without area, which stays as it is.
std::vector<char> pointsToKeep(const ExactSolid& s, const Regions& regions) {
    std::vector<char> keep(s.num_vertices(), 0);
    for (Vertex v : s.vertices()) {
        std::vector<Vertex> ends;
        for (Halfedge h : CGAL::halfedges_around_target(v, s))
            if (!regions.isFlat(s, h)) ends.push_back(s.source(h));
        keep[v.idx()] = ends.size() > 2 ||
                        (ends.size() == 2 && !CGAL::collinear_are_strictly_ordered_along_line(
                                                 s.point(ends[0]), s.point(v), s.point(ends[1])));
        if (ends.size() == 1) throw std::runtime_error("a point with one crease");
    }
    for (Face f : s.faces()) {
        const Halfedge h = s.halfedge(f);
        if (CGAL::collinear(s.point(s.source(h)), s.point(s.target(h)), s.point(s.target(s.next(h)))))
            for (Vertex v : CGAL::vertices_around_face(h, s)) keep[v.idx()] = 1;
    }
    return keep;
}

// The region's outline: each crease edge of the region from a kept point,
// followed along the creases through dropped points to the next.
void regionOutline(const ExactSolid& s, const std::vector<Face>& region, const Regions& regions,
                   const std::vector<char>& keep, std::vector<std::pair<Vertex, Vertex>>& outline) {
    outline.clear();
    for (Face f : region) {
        for (Halfedge h : CGAL::halfedges_around_face(s.halfedge(f), s)) {
            if (regions.isFlat(s, h) || !keep[s.source(h).idx()]) continue;
            Halfedge end = h;
            for (std::size_t steps = 0; !keep[s.target(end).idx()]; ++steps) {
                if (steps > s.num_halfedges()) throw std::runtime_error("an outline that does not close");
                Halfedge next = s.next(end);
                while (regions.isFlat(s, next)) next = s.next(s.opposite(next));
                end = next;
            }
            outline.emplace_back(s.source(h), s.target(end));
        }
    }
    if (outline.size() < 3) throw std::runtime_error("a region without an outline");
}

// The outline of the region `sample` lies in, triangulated as seen along the
// axis its plane's normal is longest on (never zero), appended to `out`.
void triangulateOutline(const ExactSolid& s, const std::vector<std::pair<Vertex, Vertex>>& outline, Face sample,
                        std::vector<Triangle>& out) {
    const Halfedge h = s.halfedge(sample);
    const Kernel::Vector_3 n = CGAL::normal(s.point(s.source(h)), s.point(s.target(h)), s.point(s.target(s.next(h))));
    const std::array<double, 3> size{std::abs(CGAL::to_double(n.x())), std::abs(CGAL::to_double(n.y())),
                                     std::abs(CGAL::to_double(n.z()))};
    const auto axis = std::max_element(size.begin(), size.end()) - size.begin();
    const std::size_t before = out.size();
    if (axis == 0 && CGAL::sign(n.x()) != CGAL::ZERO) triangulateRegion<CGAL::Projection_traits_yz_3<Kernel>>(s, outline, sample, out);
    else if (axis == 1 && CGAL::sign(n.y()) != CGAL::ZERO) triangulateRegion<CGAL::Projection_traits_xz_3<Kernel>>(s, outline, sample, out);
    else if (CGAL::sign(n.z()) != CGAL::ZERO) triangulateRegion<CGAL::Projection_traits_xy_3<Kernel>>(s, outline, sample, out);
    else throw std::runtime_error("a region without a plane");
    if (out.size() == before) throw std::runtime_error("a region that triangulates to nothing");
}

// The closed solid of `triangles` over the kept points of `s`, each face
// given its triangle's source.
ExactSolid solidOfTriangles(const ExactSolid& s, const std::vector<char>& keep, const std::vector<Triangle>& triangles,
                            const std::vector<std::uint64_t>& triangleSources) {
    ExactSolid out;
    std::vector<Vertex> moved(s.num_vertices());
    for (Vertex v : s.vertices())
        if (keep[v.idx()]) moved[v.idx()] = out.add_vertex(s.point(v));
    Sources outSources = out.add_property_map<Face, std::uint64_t>(kFaceSource, 0).first;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const Triangle& t = triangles[i];
        for (Vertex v : t)
            if (!keep[v.idx()]) throw std::runtime_error("a triangle on a dropped point");
        const Face f = out.add_face(moved[t[0].idx()], moved[t[1].idx()], moved[t[2].idx()]);
        if (f == ExactSolid::null_face()) throw std::runtime_error("triangles that do not join into a surface");
        outSources[f] = triangleSources[i];
    }
    for (Halfedge h : out.halfedges())
        if (out.is_border(h)) throw std::runtime_error("the joined solid is not closed");
    return out;
}

// The triangles of each region in `changing` (indices into `regions`),
// joined and triangulated afresh, in the same order. Regions share nothing
// but the solid they read (CGAL's exact kernel is thread-safe for that
// since 5.4), so they are split over the machine's cores, a few hundred at
// a time; the first error any thread meets is thrown here.
std::vector<std::vector<Triangle>> triangulatedRegions(const ExactSolid& s, const std::vector<std::vector<Face>>& regions,
                                                       const std::vector<std::size_t>& changing, const Regions& parts,
                                                       const std::vector<char>& keep) {
    std::vector<std::vector<Triangle>> out(changing.size());
    constexpr std::size_t kBatch = 256;
    std::atomic<std::size_t> nextBatch{0};
    auto work = [&] {
        std::vector<std::pair<Vertex, Vertex>> outline;
        try {
            for (std::size_t begin; (begin = nextBatch.fetch_add(kBatch)) < changing.size();) {
                for (std::size_t i = begin; i < std::min(begin + kBatch, changing.size()); ++i) {
                    const std::vector<Face>& region = regions[changing[i]];
                    regionOutline(s, region, parts, keep, outline);
                    triangulateOutline(s, outline, region.front(), out[i]);
                }
            }
        } catch (...) {
            nextBatch = changing.size();  // the other threads take no more batches
            throw;
        }
    };
    const std::size_t batches = (changing.size() + kBatch - 1) / kBatch;
    runOnThreads(static_cast<int>(std::min<std::size_t>(hardwareThreads(), batches)), work);
    return out;
}

}  // namespace

void giveFacesSources(ExactSolid& solid) {
    Sources sources = solid.add_property_map<Face, std::uint64_t>(kFaceSource, 0).first;
    std::uint64_t id = nextSource.fetch_add(solid.num_faces());
    for (Face f : solid.faces()) sources[f] = id++;
}

ExactSolid joinedCoplanarFaces(const ExactSolid& s) {
    if (s.has_garbage()) throw std::runtime_error("the solid has removed elements");
    for (Halfedge h : s.halfedges())
        if (s.is_border(h)) throw std::runtime_error("the solid is not closed");

    std::optional<Sources> sources;
    if (auto [map, found] = s.property_map<Face, std::uint64_t>(kFaceSource); found) sources = map;
    Regions parts = flatRegions(s, sources);
    const std::vector<char> keep = pointsToKeep(s, parts);
    // Each region's faces, and whether it changes.
    std::vector<std::vector<Face>> regions(s.num_faces());
    for (Face f : s.faces()) regions[findRoot(parts.parent, f.idx())].push_back(f);
    // Triangles on the region's own outline points alone already are as few
    // as any triangulation of it gives (V + 2h - 2 for V points and h
    // holes): such a region stays as it is. The others are triangulated
    // afresh, each alone.
    std::vector<std::size_t> changing;  // indices into regions, in order
    for (std::size_t r = 0; r < regions.size(); ++r) {
        bool changes = false;
        for (Face f : regions[r])
            for (Vertex v : CGAL::vertices_around_face(s.halfedge(f), s)) changes = changes || !keep[v.idx()];
        if (changes) changing.push_back(r);
    }
    const std::vector<std::vector<Triangle>> joined = triangulatedRegions(s, regions, changing, parts, keep);

    // Gathered in region order, whatever thread made which.
    std::vector<Triangle> triangles;
    triangles.reserve(s.num_faces());
    std::vector<std::uint64_t> triangleSources;  // each triangle's, where the solid has them
    auto source = [&](Face f) { return sources ? (*sources)[f] : std::uint64_t(0); };
    std::size_t next = 0;  // into changing and joined
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const std::vector<Face>& region = regions[r];
        if (next < changing.size() && changing[next] == r) {
            triangles.insert(triangles.end(), joined[next].begin(), joined[next].end());
            triangleSources.resize(triangles.size(), source(region.front()));
            ++next;
            continue;
        }
        for (Face f : region) {
            const Halfedge h = s.halfedge(f);
            triangles.push_back({s.source(h), s.target(h), s.target(s.next(h))});
            triangleSources.push_back(source(f));
        }
    }
    return solidOfTriangles(s, keep, triangles, triangleSources);
}

}  // namespace strata::exact::detail
