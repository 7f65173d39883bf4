#pragma once
// Closedness and orientation checks: image-space CSG is undefined on open solids.

#include <cstddef>
#include <string>

#include "strata/mesh/Mesh.h"

namespace strata::mesh {

struct MeshCheck {
    std::size_t boundaryEdges = 0;     // undirected edges used by one triangle
    std::size_t nonManifoldEdges = 0;  // undirected edges used by three or more triangles, not half each way
    // Edges where the solid touches itself: four or more triangles, half of
    // them running each way (two cubes sharing an edge, an extruded shape
    // whose outlines touch at a point). A valid solid, as OpenSCAD's are.
    std::size_t touchingEdges = 0;
    std::size_t misorientedEdges = 0;  // edges whose two triangles traverse them the same way
    bool inwardOriented = false;       // closed and consistent, but the signed volume is negative
    bool ok() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0 && !inwardOriented; }
    // A short phrase, "" when ok(): "not closed: 4 boundary edges",
    // "not manifold: 2 edges shared by more than two triangles",
    // "inconsistently oriented: 2 edges", "inward oriented (negative volume)";
    // several are joined with "; ".
    std::string describe() const;
};

// Judges the mesh by its geometry: vertices at exactly the same position count
// as one, so a triangle soup with repeated points is checked by topology.
// Triangles with a repeated vertex are ignored.
MeshCheck checkMesh(const Mesh& mesh);

// Merges vertices at exactly the same position (-0 and +0 alike) into the
// first of them, keeping the order of first appearance.
void mergeCoincidentVertices(Mesh& mesh);

// Merges coincident vertices, then removes triangles of zero area (and vertices
// no triangle uses). A triangle with a repeated vertex is simply removed. A
// sliver whose three distinct vertices are exactly collinear is removed after
// the triangle across its long edge is split at the sliver's middle vertex, so
// a closed mesh stays closed.
void dropDegenerateTriangles(Mesh& mesh);

}  // namespace strata::mesh
