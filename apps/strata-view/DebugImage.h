#pragma once
// The debug views, drawn on the CPU from a read-back render::Frame (a debug
// view may afford the read-back): the depth and normal AOVs as colours, the
// evaluator's form per block over the shaded image, and
// every operand's peeled layers as a grid of small images, like Fig. 8 of
// Guha et al., "Application of the two-sided depth test to CSG rendering"
// (one row per operand, for each layer its nearest and farthest surface).
// Images are RGBA8 with row 0 at the top, like Frame::rgba.

#include <cstdint>
#include <vector>

#include "strata/render/Renderer.h"

namespace strata::view {

struct DebugImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

// Near is bright, far is dark, over the frame's finite depth range; misses are black.
DebugImage depthImage(const render::Frame& frame);
// World-space normal n as the colour (n + 1) / 2; misses are black.
DebugImage normalImage(const render::Frame& frame);
// The shaded image, each 16x16 block tinted by the evaluator form that drew
// it (Frame::blockForms): green first-surface, blue register, orange
// product, pink array; blocks not drawn (constant result) dimmed.
// kFormColors[form] is the tint.
DebugImage formsImage(const render::Frame& frame);
inline constexpr std::uint8_t kFormColors[5][3] = {
    {0, 0, 0}, {0, 158, 115}, {86, 180, 233}, {230, 159, 0}, {204, 121, 167}};

// Where one small image of the peel grid lies, for its label.
struct PeelTile {
    int leaf = -1, layer = 0;
    bool far = false;            // the layer's farthest surface (else its nearest)
    int x = 0, y = 0, w = 0, h = 0;  // pixels in the grid image, y from the top
};

struct PeelGrid {
    DebugImage image;
    std::vector<PeelTile> tiles;
};

// A width x height image: per operand a block of two tiles (near, far) per
// layer, the blocks wrapped into rows so that tiles come out as large as they
// can; tiles are the frame scaled down, keeping its shape. Depth grey as in
// depthImage, over the range of all layers together so tiles compare.
PeelGrid peelGrid(const render::Frame& frame, int width, int height);

}  // namespace strata::view
