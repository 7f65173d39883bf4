#include "strata/geometry/Exact.h"

#include <string>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include "strata/core/Error.h"

namespace strata::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Solid = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Solid toSolid(const Mesh& mesh, const SourceLocation& where) {
    Solid s;
    std::vector<Solid::Vertex_index> vertices;
    vertices.reserve(mesh.positions.size());
    for (const glm::dvec3& p : mesh.positions) vertices.push_back(s.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
    for (const auto& t : mesh.triangles) {
        if (s.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == Solid::null_face()) {
            throw Error(where, "an exact evaluation cannot take this solid: it touches itself along an edge or a corner");
        }
    }
    return s;
}

Mesh toMesh(Solid& s) {
    PMP::triangulate_faces(s);
    Mesh mesh;
    std::vector<uint32_t> index(s.number_of_vertices() + s.number_of_removed_vertices(), 0);
    for (const Solid::Vertex_index v : s.vertices()) {
        const Kernel::Point_3& p = s.point(v);
        index[v] = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    for (const Solid::Face_index f : s.faces()) {
        std::array<uint32_t, 3> tri{};
        int k = 0;
        for (const Solid::Vertex_index v : CGAL::vertices_around_face(s.halfedge(f), s)) {
            if (k < 3) tri[static_cast<std::size_t>(k)] = index[v];
            ++k;
        }
        if (k == 3) mesh.triangles.push_back(tri);
    }
    return mesh;
}

}  // namespace

Mesh exactResult(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes) {
    const scene::Node& n = tree.nodes[static_cast<std::size_t>(node)];
    if (n.kind == scene::NodeKind::Leaf) return leafMeshes[static_cast<std::size_t>(n.leaf)];
    bool first = true;
    Solid result;
    for (int c : n.children) {
        const Mesh child = exactResult(tree, c, leafMeshes);
        Solid operand = toSolid(child, tree.nodes[static_cast<std::size_t>(c)].where);
        if (first) {
            result = std::move(operand);
            first = false;
            continue;
        }
        Solid out;
        bool ok = false;
        try {
            if (n.kind == scene::NodeKind::Difference) ok = PMP::corefine_and_compute_difference(result, operand, out);
            else if (n.kind == scene::NodeKind::Intersection) ok = PMP::corefine_and_compute_intersection(result, operand, out);
            else ok = PMP::corefine_and_compute_union(result, operand, out);
        } catch (const std::exception& e) {
            throw Error(n.where, std::string("the exact evaluation failed: ") + e.what());
        }
        if (!ok) throw Error(n.where, "the exact evaluation failed: a solid intersects itself or is not closed");
        result = std::move(out);
    }
    return toMesh(result);
}

}  // namespace strata::geometry
