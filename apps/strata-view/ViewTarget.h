#pragma once
// The 3D view's own colour target. The CSG image is drawn into it only when
// something changed (render on demand); every window frame then just copies
// it to the window and draws the panel over it, so hovering the panel never
// re-runs the peel passes. Also where screenshots are read from.

#include <cstdint>
#include <vector>

#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"

namespace strata::view {

class ViewTarget {
public:
    // (Re)allocates when the size changes; needs a current GL context.
    void resize(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    unsigned framebuffer() const { return framebuffer_.id(); }

    // Replaces the contents with an RGBA8 image, row 0 at the top.
    void upload(const std::vector<std::uint8_t>& rgba);
    // Copies the view to the default framebuffer, its top-left corner at the
    // window's top-left (the window may be larger than a scripted view size).
    // Copies the image into the window's framebuffer with its left edge at
    // column `left` and its top at the window's top.
    void blitToWindow(int windowHeight, int left = 0) const;
    // RGBA8, row 0 at the top, as strata-render writes its PNG.
    std::vector<std::uint8_t> read() const;

private:
    int width_ = 0, height_ = 0;
    gpu::Texture color_;
    gpu::Framebuffer framebuffer_;
};

// The default framebuffer's back buffer, RGBA8, row 0 at the top.
std::vector<std::uint8_t> readWindow(int width, int height);

}  // namespace strata::view
