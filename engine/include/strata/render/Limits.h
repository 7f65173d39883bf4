#pragma once
// What the programs let a user ask of the renderer, kept here so that every
// command line, script and panel states the same bounds. Header only, and
// free of GL: a parser of options or scripts includes it alone.

namespace strata::render {

// Largest image (or view) side: llvmpipe's and most drivers' GL_MAX_TEXTURE_SIZE.
inline constexpr int kMaxImageSide = 16384;
// Largest layers per operand (RenderSettings::layers): llvmpipe's
// GL_MAX_ARRAY_TEXTURE_LAYERS is 2048, and dual peeling fills two a pass.
inline constexpr int kMaxLayers = 1024;

}  // namespace strata::render
