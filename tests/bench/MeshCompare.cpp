// strata_mesh_compare A B: the volumes of two closed meshes and the
// symmetric Hausdorff distance between their surfaces, as CGAL measures them
// (read by CGAL's readers, not strata's). For the export benchmark: an
// image-space export against the exact result of the same scene.
//
//   strata_mesh_compare exported.off exact.off
//   -> volumeA volumeB hausdorff longestSideOfB diagonalOfB
//
// The distance is the larger of the two one-sided ones, each the farthest
// of a set of points on one surface from the other surface (CGAL's AABB
// tree): every vertex and triangle centroid of that surface and 200,000
// points sampled uniformly on it. An image-space export has millions of
// triangles of a cell's size, so its vertices and centroids cover it; the
// exact result's few large faces are covered by the samples.
// STRATA_MESH_COMPARE_WHERE=1 in the environment prints, on stderr, where
// each one-sided distance is reached.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Solid = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Solid>>>;

// The farthest that points on `from` lie from the surface of `to`.
double oneSided(const Solid& from, const Solid& to) {
    Tree tree(faces(to).first, faces(to).second, to);
    tree.accelerate_distance_queries();
    std::vector<Kernel::Point_3> points;
    for (const auto v : from.vertices()) points.push_back(from.point(v));
    for (const auto f : from.faces()) {
        const auto h = from.halfedge(f);
        points.push_back(CGAL::centroid(from.point(from.source(h)), from.point(from.target(h)),
                                        from.point(from.target(from.next(h)))));
    }
    PMP::sample_triangle_mesh(from, std::back_inserter(points),
                              CGAL::parameters::use_random_uniform_sampling(true).number_of_points_on_faces(200000));
    double farthest = 0.0;
    Kernel::Point_3 where(0, 0, 0);
    for (const Kernel::Point_3& p : points) {
        const double d = CGAL::squared_distance(p, tree.closest_point(p));
        if (d > farthest) {
            farthest = d;
            where = p;
        }
    }
    if (std::getenv("STRATA_MESH_COMPARE_WHERE"))
        std::fprintf(stderr, "farthest at %g %g %g: %g\n", where.x(), where.y(), where.z(), std::sqrt(farthest));
    return std::sqrt(farthest);
}

bool read(const char* path, Solid& s) {
    if (!CGAL::IO::read_polygon_mesh(path, s) || s.is_empty()) {
        std::fprintf(stderr, "strata_mesh_compare: cannot read a mesh from %s\n", path);
        return false;
    }
    PMP::triangulate_faces(s);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: strata_mesh_compare A B\n");
        return 2;
    }
    Solid a, b;
    if (!read(argv[1], a) || !read(argv[2], b)) return 1;
    const CGAL::Bbox_3 box = PMP::bbox(b);
    const double diagonal = std::sqrt((box.xmax() - box.xmin()) * (box.xmax() - box.xmin()) +
                                      (box.ymax() - box.ymin()) * (box.ymax() - box.ymin()) +
                                      (box.zmax() - box.zmin()) * (box.zmax() - box.zmin()));
    const double ab = oneSided(a, b), ba = oneSided(b, a);
    const double longest =
        std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
    std::printf("%.9g %.9g %.9g %.9g %.9g\n", PMP::volume(a), PMP::volume(b), std::max(ab, ba), longest, diagonal);
    return 0;
}
