#pragma once
// Buffer: one GL buffer object with immutable storage (glNamedBufferStorage).
//
// Its size is fixed at creation; to grow, make a new Buffer. Bytes in and out
// go through spans, so callers pass std::vector, std::array or raw memory.

#include <algorithm>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "strata/gpu/GlName.h"

namespace strata::gpu {

class Buffer {
public:
    Buffer() = default;  // holds no object (id() == 0)

    // `bytes` of storage, filled from `data` when it is not null (then data must
    // hold `bytes` bytes), else left undefined. `flags` as glNamedBufferStorage:
    // GL_DYNAMIC_STORAGE_BIT lets upload() write later; add GL_MAP_READ_BIT etc.
    // as needed. A size of 0 is raised to 4 bytes (GL rejects empty storage).
    Buffer(std::string_view label, std::size_t bytes, const void* data = nullptr,
           GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);

    // A buffer holding exactly `data`.
    template <class T>
    static Buffer fromSpan(std::string_view label, std::span<const T> data,
                           GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
        return Buffer(label, data.size_bytes(), data.data(), flags);
    }

    // Writes `data` at byte `offset` (glNamedBufferSubData); needs GL_DYNAMIC_STORAGE_BIT.
    void upload(std::span<const std::byte> data, std::size_t offset = 0);
    template <class T>
    void uploadSpan(std::span<const T> data, std::size_t offset = 0) {
        upload(std::as_bytes(data), offset);
    }

    // Writes `data` from offset 0 into `buffer`, first replacing it with one of
    // twice the size when it is too small (for data rebuilt every frame).
    template <class T>
    static void uploadGrowing(Buffer& buffer, std::string_view label, const std::vector<T>& data) {
        const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), sizeof(T));
        if (buffer.size() < bytes) buffer = Buffer(label, bytes * 2, nullptr, GL_DYNAMIC_STORAGE_BIT);
        if (!data.empty()) buffer.uploadSpan(std::span<const T>(data));
    }

    // Reads `out.size()` bytes from byte `offset` (glGetNamedBufferSubData; waits for the GPU).
    void download(std::span<std::byte> out, std::size_t offset = 0) const;
    template <class T>
    void downloadSpan(std::span<T> out, std::size_t offset = 0) const {
        download(std::as_writable_bytes(out), offset);
    }

    // Fills the whole buffer with zero bytes (glClearNamedBufferData).
    void clearToZero();

    // Binds to an indexed target: GL_SHADER_STORAGE_BUFFER, GL_UNIFORM_BUFFER,
    // GL_ATOMIC_COUNTER_BUFFER, GL_TRANSFORM_FEEDBACK_BUFFER.
    void bindBase(GLenum target, GLuint index) const;
    // Binds to a non-indexed target (GL_DRAW_INDIRECT_BUFFER, GL_PIXEL_PACK_BUFFER, ...).
    void bind(GLenum target) const;

    GLuint id() const noexcept { return name_.get(); }
    std::size_t size() const noexcept { return size_; }

private:
    GlName<BufferDeleter> name_;
    std::size_t size_ = 0;
};

}  // namespace strata::gpu
