#include "NefPolyhedra.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <glm/geometric.hpp>

namespace strata::exact {

using mesh::Mesh;

namespace {

using detail::Boolean;
using detail::ExactSolid;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Nef = CGAL::Nef_polyhedron_3<Exact>;
using Solid = CGAL::Surface_mesh<Exact::Point_3>;

// Two faces meeting at less than 0.1 degrees count as flat: the limit
// OpenSCAD sets for calling a mesh convex (the quads of its spheres are flat
// only up to rounding).
const double kFlatFold = std::cos(0.1 * 3.14159265358979323846 / 180.0);

std::uint64_t edgeKey(uint32_t a, uint32_t b) { return (std::uint64_t(a) << 32) | b; }

// Union-find over triangles, for the count of connected surfaces.
int findRoot(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
        parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        i = parent[static_cast<std::size_t>(i)];
    }
    return i;
}

// The corners of a volume's outer shell.
class ShellCorners {
public:
    explicit ShellCorners(std::vector<glm::dvec3>& out) : out_(out) {}
    void visit(Nef::Vertex_const_handle v) {
        const Exact::Point_3& p = v->point();
        out_.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    void visit(Nef::Halfedge_const_handle) {}
    void visit(Nef::Halffacet_const_handle) {}
    void visit(Nef::SHalfedge_const_handle) {}
    void visit(Nef::SHalfloop_const_handle) {}
    void visit(Nef::SFace_const_handle) {}

private:
    std::vector<glm::dvec3>& out_;
};

// CGAL's exception (a failed check spans several lines) as one line naming `where`.
[[noreturn]] void failed(const SourceLocation& where, const char* what, const std::exception& e) {
    std::string why = e.what();
    for (char& c : why)
        if (c == '\n') c = ' ';
    throw Error(where, what + why);
}

// The Nef polyhedron of a closed, outward solid that may have several
// shells. CGAL's constructor takes each connected shell as the boundary of
// a filled volume, so an inner shell (a void, whose faces point into it)
// would come back filled. The shells of a solid do not cross, so a point
// is in the solid exactly when an odd number of shells enclose it: the
// solid is the symmetric difference of the volumes the shells enclose
// (a void's shell turned the right way out first), which also keeps an
// island inside a void.
Nef nefOf(const ExactSolid& solid) {
    // CGAL takes a mesh that is not a valid closed halfedge mesh on trust
    // (its checks are off in a release build) and may crash on it.
    if (!CGAL::is_valid_polygon_mesh(solid) || !CGAL::is_closed(solid))
        throw std::runtime_error("the solid is not a closed manifold mesh");
    std::vector<ExactSolid> shells;
    CGAL::Polygon_mesh_processing::split_connected_components(solid, shells);
    if (shells.size() <= 1) return Nef(solid);
    Nef result;
    for (ExactSolid& shell : shells) {
        if (CGAL::Polygon_mesh_processing::volume(shell) < 0)
            CGAL::Polygon_mesh_processing::reverse_face_orientations(shell);
        result ^= Nef(shell);
    }
    return result;
}

// The mesh of a Nef polyhedron's boundary. A result may touch itself at a
// corner or along an edge (two parts of a difference meeting at a point),
// which a halfedge mesh cannot hold as one vertex or edge: there the soup's
// point is duplicated, one for each part, so that the mesh stays valid,
// its parts touching (CGAL's own conversion builds an invalid mesh there).
// The Nef's faces are already oriented outward; orienting the soup only
// splits what touches.
ExactSolid meshOfNef(const Nef& nef) {
    std::vector<Exact::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    CGAL::convert_nef_polyhedron_to_polygon_soup(nef, points, polygons, /*triangulate_all_faces=*/true);
    CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
    ExactSolid out;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, out);
    return out;
}

}  // namespace

namespace detail {

bool isConvex(const Mesh& closed) {
    if (closed.triangles.empty()) return false;
    // Each directed edge's triangle; a directed edge met twice is not manifold.
    std::unordered_map<std::uint64_t, uint32_t> owner;
    owner.reserve(closed.triangles.size() * 3);
    for (uint32_t t = 0; t < closed.triangles.size(); ++t) {
        const auto& tri = closed.triangles[t];
        for (int k = 0; k < 3; ++k) {
            if (!owner.emplace(edgeKey(tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]), t).second) {
                return false;
            }
        }
    }
    auto normal = [&](const std::array<uint32_t, 3>& t) {
        const glm::dvec3 n = glm::cross(closed.positions[t[1]] - closed.positions[t[0]],
                                        closed.positions[t[2]] - closed.positions[t[0]]);
        const double length = glm::length(n);
        return length > 0.0 ? n / length : n;
    };
    std::vector<int> parent(closed.triangles.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (uint32_t t = 0; t < closed.triangles.size(); ++t) {
        const auto& tri = closed.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = tri[static_cast<std::size_t>(k)], b = tri[static_cast<std::size_t>((k + 1) % 3)];
            const auto across = owner.find(edgeKey(b, a));
            if (across == owner.end()) return false;  // not closed
            const auto& other = closed.triangles[across->second];
            uint32_t d = other[0];
            for (uint32_t v : other)
                if (v != a && v != b) d = v;
            // A fold is reflex when the neighbour's far corner lies outside
            // this triangle's plane (outward: counter-clockwise seen from
            // outside); folds flatter than 0.1 degrees pass, as in OpenSCAD.
            const glm::dvec3 n = normal(tri);
            if (glm::dot(closed.positions[d] - closed.positions[tri[0]], n) > 0.0 &&
                glm::dot(n, normal(other)) < kFlatFold) {
                return false;
            }
            const int ra = findRoot(parent, static_cast<int>(t)), rb = findRoot(parent, static_cast<int>(across->second));
            if (ra != rb) parent[static_cast<std::size_t>(ra)] = rb;
        }
    }
    const int root = findRoot(parent, 0);
    for (std::size_t t = 1; t < parent.size(); ++t)
        if (findRoot(parent, static_cast<int>(t)) != root) return false;
    return true;
}

}  // namespace detail

std::vector<std::vector<glm::dvec3>> convexParts(const Mesh& closed, const SourceLocation& where) {
    if (detail::isConvex(closed)) return {closed.positions};
    const Solid solid = detail::toExactSolid(closed, where, "minkowski's convex decomposition");
    std::vector<std::vector<glm::dvec3>> parts;
    try {
        Nef nef = nefOf(solid);
        CGAL::convex_decomposition_3(nef);
        // The first volume is the unbounded outside; the marked ones are the parts.
        auto volume = nef.volumes_begin();
        for (++volume; volume != nef.volumes_end(); ++volume) {
            if (!volume->mark()) continue;
            std::vector<glm::dvec3> corners;
            ShellCorners visitor(corners);
            nef.visit_shell_objects(Nef::SFace_const_handle(volume->shells_begin()), visitor);
            parts.push_back(std::move(corners));
        }
    } catch (const std::exception& e) {
        failed(where, "minkowski cannot split this solid into convex parts: ", e);
    }
    return parts;
}

namespace detail {

ExactSolid toExactSolid(const Mesh& mesh, const SourceLocation& where, const char* who) {
    std::vector<Exact::Point_3> points;
    points.reserve(mesh.positions.size());
    for (const glm::dvec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
    return toExactSolid(points, mesh, where, who);
}

ExactSolid toExactSolid(const std::vector<Exact::Point_3>& points, const Mesh& mesh, const SourceLocation& where,
                        const char* who) {
    ExactSolid s;
    std::vector<ExactSolid::Vertex_index> vertices;
    vertices.reserve(points.size());
    for (const Exact::Point_3& p : points) vertices.push_back(s.add_vertex(p));
    for (const auto& t : mesh.triangles) {
        if (s.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == ExactSolid::null_face()) {
            throw Error(where, std::string(who) + " cannot take this solid: it touches itself along an edge or a corner");
        }
    }
    return s;
}

ExactSolid simplified(const ExactSolid& solid, const SourceLocation& where) {
    // Nothing to join on an empty solid, nor on one that encloses nothing.
    if (solid.number_of_faces() == 0 || CGAL::Polygon_mesh_processing::volume(solid) == 0) return ExactSolid{};
    try {
        return meshOfNef(nefOf(solid));
    } catch (const std::exception& e) {
        failed(where, "the exact evaluation failed: ", e);
    }
}

ExactSolid nefBoolean(const ExactSolid& a, const ExactSolid& b, Boolean op, const SourceLocation& where) {
    try {
        Nef left = nefOf(a);
        const Nef right = nefOf(b);
        if (op == Boolean::Union) left += right;
        else if (op == Boolean::Intersection) left *= right;
        else left -= right;
        return meshOfNef(left);
    } catch (const std::exception& e) {
        failed(where, "the exact evaluation failed: ", e);
    }
}

}  // namespace detail
}  // namespace strata::exact
