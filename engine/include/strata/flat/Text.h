#pragma once
// text(): glyph outlines as OpenSCAD 2021.01 makes them (FreeType, HarfBuzz,
// fontconfig), before they are unioned.

#include <vector>

#include "strata/flat/Outlines.h"
#include "strata/scene/Flat.h"

namespace strata::flat {

// One Outlines per glyph, in text coordinates (size, spacing, direction and
// alignment applied), marked sanitized as OpenSCAD marks them: the union keeps
// each contour's own orientation (outer outlines counter-clockwise) and skips
// the even-odd clean-up. A font that fontconfig cannot resolve
// falls back as OpenSCAD's does; a failure of the font libraries throws
// strata::Error with no position (the caller adds the node's).
std::vector<Outlines> textGlyphs(const scene::Text& text);

}  // namespace strata::flat
