#pragma once
// What one contouring met on the way, for tests that must know a rare case
// was exercised (ambiguous faces, the flips that keep the mesh 2-manifold).

#include <cstddef>

#include "strata/contour/Contour.h"
#include "strata/contour/Dexels.h"
#include "strata/contour/Planes.h"
#include "strata/mesh/Mesh.h"

namespace strata::contour {

struct ContourStats {
    std::size_t ambiguousFaces = 0;   // cell faces with alternating corner signs, each counted once
    std::size_t flippedFaces = 0;     // of those, the ones whose pairing was flipped (CellTopology.h)
    std::size_t clampedVertices = 0;  // patch vertices whose QEF minimizer left their cell
    std::size_t unsnappedVertices = 0;  // vertices put back off their planes where snapping folded the mesh
    std::size_t mergedVertices = 0;   // vertices the flat regions' merge removed (FlatRegions.h)
    std::size_t tangles = 0;          // places the first merged mesh crossed itself (FindTangles)
    std::size_t untangleRounds = 0;   // rounds that moved vertices to their crossings' means
    std::size_t untangledVertices = 0;  // vertices those rounds moved
    std::size_t tanglesLeft = 0;      // places the returned mesh crosses itself
};

// contour(), counting as it goes.
mesh::Mesh contourCounting(const Dexels& dexels, ContourStats& stats, const PlaneTable* planes = nullptr,
                           const FindTangles& findTangles = {});

}  // namespace strata::contour
