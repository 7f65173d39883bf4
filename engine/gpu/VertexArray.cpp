#include "strata/gpu/VertexArray.h"

#include "strata/gpu/Buffer.h"

namespace strata::gpu {

VertexArray::VertexArray(std::string_view label) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    name_ = GlName<VertexArrayDeleter>(id);
    setLabel(GL_VERTEX_ARRAY, id, label);
}

void VertexArray::setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, int stride) {
    glVertexArrayVertexBuffer(id(), binding, buffer.id(), static_cast<GLintptr>(offset), stride);
}

void VertexArray::setBindingDivisor(GLuint binding, GLuint divisor) {
    glVertexArrayBindingDivisor(id(), binding, divisor);
}

void VertexArray::setElementBuffer(const Buffer& buffer) { glVertexArrayElementBuffer(id(), buffer.id()); }

void VertexArray::setAttribute(GLuint location, GLuint binding, int components, GLenum type,
                               std::size_t relativeOffset, bool normalized) {
    glEnableVertexArrayAttrib(id(), location);
    glVertexArrayAttribFormat(id(), location, components, type, normalized ? GL_TRUE : GL_FALSE,
                              static_cast<GLuint>(relativeOffset));
    glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::bind() const { glBindVertexArray(id()); }

}  // namespace strata::gpu
