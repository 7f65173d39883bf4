#pragma once
// Private to FlatImport*.cpp: the two readers behind importFlat() and what
// they share.

#include <string>
#include <string_view>

#include "strata/geometry/Outlines.h"
#include "strata/scene/Flat.h"

namespace strata::geometry::detail {

// DXF as OpenSCAD 2021.01's DxfData reads it: the unsanitized outlines.
Outlines importDxf(const scene::FlatImport& import, const std::string& text);

// SVG as OpenSCAD 2021.01's libsvg + import_svg read it: already the union of
// the shapes (each cleaned with an even-odd union, then all unioned), so the
// result comes back sanitized.
Outlines importSvg(const scene::FlatImport& import, const std::string& text);

// "'path'", quoted for messages.
std::string quotedPath(std::string_view path);

}  // namespace strata::geometry::detail
