#include "strata/gpu/Framebuffer.h"

#include "strata/gpu/Check.h"
#include "strata/gpu/Texture.h"

namespace strata::gpu {

Framebuffer::Framebuffer(std::string_view label) : label_(label) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    name_ = GlName<FramebufferDeleter>(id);
    setLabel(GL_FRAMEBUFFER, id, label);
}

void Framebuffer::attachTexture(GLenum attachment, const Texture& texture, int level) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attachLayer(GLenum attachment, const Texture& texture, int layer, int level) {
    glNamedFramebufferTextureLayer(id(), attachment, texture.id(), level, layer);
}

void Framebuffer::detach(GLenum attachment) { glNamedFramebufferTexture(id(), attachment, 0, 0); }

void Framebuffer::setDrawBuffers(std::initializer_list<GLenum> buffers) {
    setDrawBuffers(std::span<const GLenum>(buffers.begin(), buffers.size()));
}

void Framebuffer::setDrawBuffers(std::span<const GLenum> buffers) {
    glNamedFramebufferDrawBuffers(id(), static_cast<GLsizei>(buffers.size()), buffers.data());
}

void Framebuffer::setReadBuffer(GLenum buffer) { glNamedFramebufferReadBuffer(id(), buffer); }

GLenum Framebuffer::status() const { return glCheckNamedFramebufferStatus(id(), GL_DRAW_FRAMEBUFFER); }

void Framebuffer::checkComplete(std::source_location where) const {
    const GLenum s = status();
    if (s == GL_FRAMEBUFFER_COMPLETE) return;
    fail("incomplete framebuffer '" + label_ + "' (" + enumName(s) + ")", where);
}

void Framebuffer::clearColor(int drawBuffer, const float rgba[4]) {
    glClearNamedFramebufferfv(id(), GL_COLOR, drawBuffer, rgba);
}

void Framebuffer::clearColorInt(int drawBuffer, const GLint rgba[4]) {
    glClearNamedFramebufferiv(id(), GL_COLOR, drawBuffer, rgba);
}

void Framebuffer::clearDepth(float depth) { glClearNamedFramebufferfv(id(), GL_DEPTH, 0, &depth); }

void Framebuffer::bindForDraw() const { glBindFramebuffer(GL_DRAW_FRAMEBUFFER, id()); }
void Framebuffer::bindForRead() const { glBindFramebuffer(GL_READ_FRAMEBUFFER, id()); }
void Framebuffer::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }
void Framebuffer::bindDefault() { glBindFramebuffer(GL_FRAMEBUFFER, 0); }

}  // namespace strata::gpu
