#pragma once
// Closedness and orientation checks: image-space CSG is undefined on open solids.

#include <cstddef>
#include <string>

#include "strata/geometry/Mesh.h"

namespace strata::geometry {

struct MeshCheck {
    std::size_t boundaryEdges = 0;     // undirected edges used by one triangle
    std::size_t nonManifoldEdges = 0;  // undirected edges used by three or more triangles
    std::size_t misorientedEdges = 0;  // edges whose two triangles traverse them the same way
    bool inwardOriented = false;       // closed and consistent, but the signed volume is negative
    bool ok() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0 && !inwardOriented; }
    std::string describe() const;      // "open: 4 boundary edges", ... ; "" when ok()
};

MeshCheck checkMesh(const Mesh& mesh);

// Removes triangles of zero area (and vertices no triangle uses).
void dropDegenerateTriangles(Mesh& mesh);

}  // namespace strata::geometry
