#include "MeshInspection.h"

#include <algorithm>
#include <array>
#include <functional>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Surface_mesh.h>

namespace strata::contour::test {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

std::string MeshInspection::describe() const {
    std::string s;
    s += soupIsManifold ? "" : " not-a-manifold-soup";
    s += valid ? "" : " invalid";
    s += closed ? "" : " open";
    s += outward ? "" : " not-outward";
    s += selfIntersects ? " self-intersecting" : "";
    s += degenerate == 0 ? "" : " degenerate:" + std::to_string(degenerate);
    s += " V=" + std::to_string(vertices) + " E=" + std::to_string(edges) + " F=" + std::to_string(faces) +
         " components=" + std::to_string(components) + " volume=" + std::to_string(volume);
    return s;
}

MeshInspection inspect(const mesh::Mesh& mesh, bool lookForSelfIntersections) {
    MeshInspection r;
    std::vector<Point> points;
    points.reserve(mesh.positions.size());
    for (const glm::dvec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
    std::vector<std::array<std::size_t, 3>> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) triangles.push_back({t[0], t[1], t[2]});
    r.soupIsManifold = PMP::is_polygon_soup_a_polygon_mesh(triangles);
    if (!r.soupIsManifold) return r;

    SurfaceMesh sm;
    PMP::polygon_soup_to_polygon_mesh(points, triangles, sm);
    r.valid = CGAL::is_valid_polygon_mesh(sm);
    r.closed = CGAL::is_closed(sm);
    r.vertices = long(sm.number_of_vertices());
    r.edges = long(sm.number_of_edges());
    r.faces = long(sm.number_of_faces());
    for (const auto f : sm.faces()) r.degenerate += PMP::is_degenerate_triangle_face(f, sm) ? 1 : 0;
    auto componentOf = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:component").first;
    r.components = PMP::connected_components(sm, componentOf);
    // A fresh Surface_mesh numbers its faces in the soup's order.
    for (const auto f : sm.faces()) r.componentOfTriangle.push_back(componentOf[f]);
    if (lookForSelfIntersections && r.degenerate == 0) r.selfIntersects = PMP::does_self_intersect(sm);
    if (r.closed) {
        // Every connected component outward, or inward where it lies inside
        // an odd number of others (a cavity): CGAL's own test for one mesh
        // looks only at the component with the extreme vertex.
        std::vector<bool> componentOutward;
        std::vector<std::size_t> nesting;
        auto volumeOf = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:volume").first;
        PMP::volume_connected_components(sm, volumeOf,
                                         PMP::parameters::is_cc_outward_oriented(std::ref(componentOutward))
                                             .nesting_levels(std::ref(nesting)));
        r.outward = !componentOutward.empty();
        for (std::size_t c = 0; c < componentOutward.size(); ++c) {
            r.outward = r.outward && componentOutward[c] == (nesting[c] % 2 == 0);
        }
        r.volume = PMP::volume(sm);
    }
    return r;
}

}  // namespace strata::contour::test
