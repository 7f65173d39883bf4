#pragma once
// Framebuffer: one GL framebuffer object with texture attachments.
//
// Attach, set the draw buffers, then checkComplete(): an incomplete framebuffer
// throws a strata::Error naming GL's status and the caller's source position:
//   engine/render/PeelPass.cpp:58: incomplete framebuffer 'peel' (GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT)

#include <initializer_list>
#include <source_location>
#include <span>
#include <string>
#include <string_view>

#include "strata/gpu/GlName.h"

namespace strata::gpu {

class Texture;

class Framebuffer {
public:
    Framebuffer() = default;  // holds no object (id() == 0)
    explicit Framebuffer(std::string_view label);

    // Attaches level `level` of `texture`; for an array texture all layers
    // (layered rendering: gl_Layer picks the layer). `attachment` is
    // GL_COLOR_ATTACHMENTi, GL_DEPTH_ATTACHMENT, GL_STENCIL_ATTACHMENT or GL_DEPTH_STENCIL_ATTACHMENT.
    void attachTexture(GLenum attachment, const Texture& texture, int level = 0);
    // Attaches one layer of an array texture.
    void attachLayer(GLenum attachment, const Texture& texture, int layer, int level = 0);
    // Removes whatever is attached at `attachment`.
    void detach(GLenum attachment);

    // glNamedFramebufferDrawBuffers / glNamedFramebufferReadBuffer.
    void setDrawBuffers(std::initializer_list<GLenum> buffers);
    void setDrawBuffers(std::span<const GLenum> buffers);
    void setReadBuffer(GLenum buffer);

    // Throws strata::Error unless the framebuffer is complete for drawing.
    void checkComplete(std::source_location where = std::source_location::current()) const;
    // GL's status (GL_FRAMEBUFFER_COMPLETE when complete).
    GLenum status() const;

    // Clears draw buffer `drawBuffer` (an index into setDrawBuffers) to a value.
    void clearColor(int drawBuffer, const float rgba[4]);
    void clearColorInt(int drawBuffer, const GLint rgba[4]);
    void clearDepth(float depth);

    void bindForDraw() const;  // GL_DRAW_FRAMEBUFFER
    void bindForRead() const;  // GL_READ_FRAMEBUFFER
    void bind() const;         // both
    // Binds the default framebuffer (the window's, or none for a headless Context).
    static void bindDefault();

    GLuint id() const noexcept { return name_.get(); }
    const std::string& label() const noexcept { return label_; }

private:
    GlName<FramebufferDeleter> name_;
    std::string label_;
};

}  // namespace strata::gpu
