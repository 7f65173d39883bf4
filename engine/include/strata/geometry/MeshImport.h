#pragma once
// Mesh files through OpenMesh: STL (ascii and binary), OFF, OBJ, PLY.

#include <string>

#include "strata/geometry/Mesh.h"

namespace strata::geometry {

// Reads a triangle mesh, with coincident vertices merged. Throws strata::Error
// naming the file when it cannot be read.
Mesh importMesh(const std::string& path);

}  // namespace strata::geometry
