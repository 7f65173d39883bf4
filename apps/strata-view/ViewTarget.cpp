#include "ViewTarget.h"

#include <algorithm>

#include "strata/gpu/Gl.h"

namespace strata::view {
namespace {

// GL's rows are bottom-up; image files' top-down.
void flipRows(std::vector<std::uint8_t>& rgba, int width, int height) {
    const auto row = static_cast<std::ptrdiff_t>(width) * 4;
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(rgba.begin() + y * row, rgba.begin() + (y + 1) * row, rgba.begin() + (height - 1 - y) * row);
}

std::vector<std::uint8_t> readBound(int width, int height) {
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    flipRows(rgba, width, height);
    return rgba;
}

}  // namespace

void ViewTarget::resize(int width, int height) {
    if (width == width_ && height == height_ && framebuffer_.id() != 0) return;
    width_ = width;
    height_ = height;
    framebuffer_ = gpu::Framebuffer();  // the old framebuffer goes before its texture
    color_ = gpu::Texture::create2D("strata-view colour", GL_RGBA8, width, height);
    framebuffer_ = gpu::Framebuffer("strata-view");
    framebuffer_.attachTexture(GL_COLOR_ATTACHMENT0, color_);
    framebuffer_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    framebuffer_.setReadBuffer(GL_COLOR_ATTACHMENT0);
    framebuffer_.checkComplete();
}

void ViewTarget::upload(const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> flipped = rgba;
    flipRows(flipped, width_, height_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    color_.upload(0, 0, 0, width_, height_, 1, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
}

void ViewTarget::blitToWindow(int windowHeight, int left) const {
    glBlitNamedFramebuffer(framebuffer_.id(), 0, 0, 0, width_, height_, left, windowHeight - height_, left + width_,
                           windowHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

std::vector<std::uint8_t> ViewTarget::read() const {
    framebuffer_.bindForRead();
    std::vector<std::uint8_t> rgba = readBound(width_, height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return rgba;
}

std::vector<std::uint8_t> readWindow(int width, int height) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    return readBound(width, height);
}

}  // namespace strata::view
