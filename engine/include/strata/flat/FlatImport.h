#pragma once
// import() of a 2D file: DXF (through dxflib) or SVG, read as OpenSCAD 2021.01
// reads them.

#include "strata/flat/Outlines.h"
#include "strata/scene/Flat.h"

namespace strata::flat {

// The file's closed outlines: a DXF's as drawn (unsanitized), an SVG's already
// the union of its shapes (sanitized), as OpenSCAD's readers return them. Throws strata::Error (no position:
// the caller adds the node's) when the file cannot be read or is malformed.
Outlines importFlat(const scene::FlatImport& import);

}  // namespace strata::flat
