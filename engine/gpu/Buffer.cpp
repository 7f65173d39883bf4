#include "strata/gpu/Buffer.h"

#include <algorithm>

#include "strata/gpu/Check.h"

namespace strata::gpu {

Buffer::Buffer(std::string_view label, std::size_t bytes, const void* data, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    name_ = GlName<BufferDeleter>(id);
    // GL rejects zero-sized storage; an empty scene still wants a bindable buffer.
    size_ = std::max<std::size_t>(bytes, 4);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(size_), bytes == 0 ? nullptr : data, flags);
    setLabel(GL_BUFFER, id, label);
}

void Buffer::upload(std::span<const std::byte> data, std::size_t offset) {
    if (data.empty()) return;
    if (offset + data.size() > size_) fail("Buffer::upload past the end of the buffer");
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(data.size()),
                         data.data());
}

void Buffer::download(std::span<std::byte> out, std::size_t offset) const {
    if (out.empty()) return;
    if (offset + out.size() > size_) fail("Buffer::download past the end of the buffer");
    glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(out.size()),
                            out.data());
}

void Buffer::clearToZero() {
    const GLuint zero = 0;
    glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void Buffer::bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }

void Buffer::bind(GLenum target) const { glBindBuffer(target, id()); }

}  // namespace strata::gpu
