#pragma once
// GlName<Deleter>: sole ownership of one OpenGL object name.
//
// Move-only. A moved-from GlName holds 0, and deleting 0 is never attempted,
// so a wrapper built on it (Buffer, Texture, ...) is safe to move around and to
// destroy in any order before the context goes. Deleters call glDelete*.

#include <utility>

#include "strata/gpu/Gl.h"

namespace strata::gpu {

template <class Deleter>
class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint id) noexcept : id_(id) {}
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;
    GlName(GlName&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlName& operator=(GlName&& other) noexcept {
        std::swap(id_, other.id_);  // the old name is deleted with `other`
        return *this;
    }
    ~GlName() {
        if (id_ != 0) Deleter{}(id_);
    }

    GLuint get() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }

private:
    GLuint id_ = 0;
};

struct BufferDeleter {
    void operator()(GLuint id) const { glDeleteBuffers(1, &id); }
};
struct TextureDeleter {
    void operator()(GLuint id) const { glDeleteTextures(1, &id); }
};
struct FramebufferDeleter {
    void operator()(GLuint id) const { glDeleteFramebuffers(1, &id); }
};
struct ProgramDeleter {
    void operator()(GLuint id) const { glDeleteProgram(id); }
};
struct ShaderDeleter {
    void operator()(GLuint id) const { glDeleteShader(id); }
};
struct QueryDeleter {
    void operator()(GLuint id) const { glDeleteQueries(1, &id); }
};
struct VertexArrayDeleter {
    void operator()(GLuint id) const { glDeleteVertexArrays(1, &id); }
};

}  // namespace strata::gpu
