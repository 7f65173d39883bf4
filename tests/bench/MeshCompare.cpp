// strata_mesh_compare A B: the volumes of two closed meshes and the
// symmetric Hausdorff distance between their surfaces, as CGAL measures them
// (read by CGAL's readers, not strata's). For the export benchmark: an
// image-space export against the exact result of the same scene.
//
//   strata_mesh_compare exported.off exact.off
//   -> volumeA volumeB hausdorff longestSideOfB diagonalOfB
//
// The distance is CGAL's approximate Hausdorff distance, sampled on both
// surfaces at a density of 1/4000 of B's box diagonal.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Solid = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

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
    const double step = diagonal / 4000.0;
    const auto sampling = CGAL::parameters::use_grid_sampling(true).grid_spacing(step);
    const double ab = PMP::approximate_Hausdorff_distance<CGAL::Parallel_if_available_tag>(a, b, sampling);
    const double ba = PMP::approximate_Hausdorff_distance<CGAL::Parallel_if_available_tag>(b, a, sampling);
    const double longest =
        std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
    std::printf("%.9g %.9g %.9g %.9g %.9g\n", PMP::volume(a), PMP::volume(b), std::max(ab, ba), longest, diagonal);
    return 0;
}
