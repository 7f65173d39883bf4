#pragma once
// Writing a 2D result as a drawing, the format chosen by the extension: SVG
// or DXF, laid out as OpenSCAD 2021.01 writes them (so OpenSCAD's import()
// and the usual CAM tools read them), with every coordinate written so that
// it reads back to the same double. Staged, then committed, as the meshes are.

#include <string>
#include <vector>

#include "strata/flat/Outlines.h"
#include "strata/io/ImageWriter.h"

namespace strata::io {

enum class FlatFormat { Svg, Dxf };

// Whether `path` names a 2D drawing by its extension (any case: .svg, .dxf).
bool isFlatPath(const std::string& path);
// The format of a path isFlatPath accepts.
FlatFormat flatFormatOf(const std::string& path);

// The outlines' bytes in `format`. SVG: one path of every outline (y turned
// down, as SVG's axis runs, the view box the outlines' box, one unit a
// millimetre); DXF: each outline as LINE entities on layer 0, between empty
// BLOCKS and OBJECTS sections.
std::vector<unsigned char> flatBytes(const flat::Outlines& outlines, FlatFormat format);

// Stages the drawing into `path` (commit() renames it into place). Throws
// strata::Error("<path>: cannot write ...") as the image writers do.
StagedFile stageFlat(const std::string& path, const flat::Outlines& outlines);

}  // namespace strata::io
