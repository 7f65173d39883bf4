#pragma once
// The contouring's output read by CGAL, not by strata: whether the triangles
// form a closed, 2-manifold, outward-oriented surface without degenerate
// triangles or self-intersections, and its volume and topology.

#include <cstddef>
#include <string>
#include <vector>

#include "strata/mesh/Mesh.h"

namespace strata::contour::test {

struct MeshInspection {
    bool soupIsManifold = false;  // PMP::is_polygon_soup_a_polygon_mesh: ≤ 2 triangles per edge, disk links, consistent
    bool valid = false;           // CGAL::is_valid_polygon_mesh
    bool closed = false;
    bool outward = false;         // every component outward, or inward inside an odd number of others
                                  // (CGAL's nesting: meaningful only without self-intersections)
    std::vector<std::size_t> componentOfTriangle;  // by the mesh's triangle order
    bool selfIntersects = false;  // only looked for when asked
    std::size_t degenerate = 0;   // triangles of zero area (exact predicate)
    std::size_t components = 0;
    long vertices = 0, edges = 0, faces = 0;
    double volume = 0.0;

    long euler() const { return vertices - edges + faces; }
    // Closed, 2-manifold, valid, outward, no degenerate triangle (and no
    // self-intersection when looked for).
    bool sound() const { return soupIsManifold && valid && closed && outward && degenerate == 0 && !selfIntersects; }
    std::string describe() const;
};

MeshInspection inspect(const mesh::Mesh& mesh, bool lookForSelfIntersections = true);

}  // namespace strata::contour::test
