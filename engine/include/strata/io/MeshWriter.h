#pragma once
// Writing a solid as a mesh file, the format chosen by the extension:
// binary STL, OFF, OBJ (as OpenSCAD and slicers read them) or 3MF (through
// lib3mf, with a colour per triangle when given). Written whole or not at
// all, as the images are (ImageWriter.h: staged, then committed).

#include <optional>
#include <span>
#include <string>

#include <glm/vec4.hpp>

#include "strata/io/ImageWriter.h"
#include "strata/mesh/Mesh.h"

namespace strata::io {

enum class MeshFormat { Stl, Off, Obj, ThreeMf };

// The format `path` names by its extension (any case): .stl, .off, .obj,
// .3mf. Throws strata::Error("<path>: cannot export to '.ext' (expected
// .stl, .off, .obj or .3mf)") for any other.
MeshFormat meshFormatOf(const std::string& path);

// The mesh's bytes in `format`. Points are written so that they read back
// bit for bit (OFF and OBJ: 17 significant digits; STL: single precision,
// as the format holds). `colors`, one RGBA in [0,1] per triangle, is used
// by 3MF only (a base material per distinct colour); empty: none.
std::vector<unsigned char> meshBytes(const mesh::Mesh& mesh, MeshFormat format,
                                     std::span<const glm::vec4> colors = {});

// Stages the mesh into `path` (commit() renames it into place). Throws
// strata::Error("<path>: cannot write ...") as the image writers do.
StagedFile stageMesh(const std::string& path, const mesh::Mesh& mesh, std::span<const glm::vec4> colors = {});

}  // namespace strata::io
