#pragma once
// Private to FlatImport*.cpp: the two readers behind importFlat() and what
// they share.

#include <climits>
#include <string>
#include <string_view>

#include "strata/flat/Outlines.h"
#include "strata/scene/Flat.h"

namespace strata::flat::detail {

// DXF as OpenSCAD 2021.01's DxfData reads it: the unsanitized outlines.
Outlines importDxf(const scene::FlatImport& import, const std::string& text);

// SVG as OpenSCAD 2021.01's libsvg + import_svg read it: already the union of
// the shapes (each cleaned with an even-odd union, then all unioned), so the
// result comes back sanitized.
Outlines importSvg(const scene::FlatImport& import, const std::string& text);

// "'path'", quoted for messages.
std::string quotedPath(std::string_view path);

// What an x86-64 build's double -> int conversion gives, as OpenSCAD's
// readers convert: the value truncated, or INT_MIN when it is NaN or out of
// range (cvttsd2si). A C++ cast of such a value is undefined.
inline int toIntX86(double v) {
    if (!(v > -2147483649.0 && v < 2147483648.0)) return INT_MIN;
    return static_cast<int>(v);
}

}  // namespace strata::flat::detail
