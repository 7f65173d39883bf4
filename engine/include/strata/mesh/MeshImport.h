#pragma once
// Mesh files through OpenMesh: STL (ascii and binary), OFF, OBJ, PLY.

#include <string>

#include "strata/mesh/Mesh.h"

namespace strata::mesh {

// Reads a mesh, with coincident vertices merged and polygons ear-clipped into
// triangles (winding kept). The extension picks the format, in any case.
// Coordinates pass through OpenMesh's readers as float. OpenMesh's console
// messages are silenced. Throws strata::Error "path: cannot read mesh: why"
// when the file is missing, unreadable, empty, of another format or holds no
// faces. Faces OpenMesh cannot attach (complex edges) are kept, so checkMesh
// reports the defect instead of it passing silently.
Mesh importMesh(const std::string& path);

}  // namespace strata::mesh
