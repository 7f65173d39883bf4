#pragma once
// VertexArray: one GL vertex array object, set up through DSA
// (glVertexArrayVertexBuffer, glVertexArrayAttribFormat, ...).
// A fullscreen pass needs one too: core profile draws need a bound VAO, even an empty one.

#include <cstddef>
#include <string_view>

#include "strata/gpu/GlName.h"

namespace strata::gpu {

class Buffer;

class VertexArray {
public:
    VertexArray() = default;  // holds no object (id() == 0)
    explicit VertexArray(std::string_view label);

    // Vertex buffer binding point `binding` reads `buffer` from byte `offset`, `stride` bytes apart.
    void setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, int stride);
    // Per-instance instead of per-vertex (divisor 1), or back (divisor 0).
    void setBindingDivisor(GLuint binding, GLuint divisor);
    // Index buffer for glDrawElements*.
    void setElementBuffer(const Buffer& buffer);

    // Enables attribute `location`, read as `components` values of `type`
    // (converted to float; `normalized` for fixed-point) at `relativeOffset`
    // within the vertex, from binding point `binding`.
    void setAttribute(GLuint location, GLuint binding, int components, GLenum type,
                      std::size_t relativeOffset, bool normalized = false);

    void bind() const;

    GLuint id() const noexcept { return name_.get(); }

private:
    GlName<VertexArrayDeleter> name_;
};

}  // namespace strata::gpu
