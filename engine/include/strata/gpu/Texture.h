#pragma once
// Texture: one GL texture with immutable storage (glTextureStorage2D/3D):
// a 2D texture or a 2D array texture (layered: one image per layer, written
// with gl_Layer or Framebuffer::attachLayer, read as sampler2DArray).

#include <cstddef>
#include <span>
#include <string_view>

#include "strata/gpu/GlName.h"

namespace strata::gpu {

// Zero means default, in the spirit of sokol's *_desc structs.
struct TextureDesc {
    GLenum target = GL_TEXTURE_2D;      // GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY
    GLenum internalFormat = GL_RGBA8;   // sized format: GL_R32F, GL_RG32F, GL_RGBA8, GL_DEPTH_COMPONENT32F, ...
    int width = 0;
    int height = 0;
    int layers = 0;                     // GL_TEXTURE_2D_ARRAY only; 0 means 1
    int levels = 0;                     // mip levels; 0 means 1
    GLenum minFilter = GL_NEAREST;      // depth layers must not be filtered
    GLenum magFilter = GL_NEAREST;
    GLenum wrap = GL_CLAMP_TO_EDGE;
};

class Texture {
public:
    Texture() = default;  // holds no object (id() == 0)
    // Throws strata::Error on a non-positive size or an unsupported target.
    Texture(std::string_view label, const TextureDesc& desc);

    static Texture create2D(std::string_view label, GLenum internalFormat, int width, int height);
    static Texture create2DArray(std::string_view label, GLenum internalFormat, int width,
                                 int height, int layers);

    // Binds to texture unit `unit` for sampling (glBindTextureUnit).
    void bindUnit(GLuint unit) const;
    // Binds level `level` to image unit `unit` for imageLoad/imageStore (every
    // layer of an array texture).
    void bindImage(GLuint unit, GLenum access, int level = 0) const;

    // Fills level `level` (every layer) with one texel value given in
    // `format`/`type` (glClearTexImage); null clears to zero.
    void clear(GLenum format, GLenum type, const void* value, int level = 0);

    // Writes a region. For a 2D texture z = 0 and depth = 1.
    void upload(int x, int y, int z, int width, int height, int depth, GLenum format, GLenum type,
                const void* pixels, int level = 0);
    // Reads a whole level (every layer, layer after layer, rows bottom first as GL stores
    // them) into `out`, which must be large enough. Pack alignment is set to 1.
    void download(GLenum format, GLenum type, std::span<std::byte> out, int level = 0) const;
    // Reads a region of one level (glGetTextureSubImage).
    void downloadRegion(int x, int y, int z, int width, int height, int depth, GLenum format,
                        GLenum type, std::span<std::byte> out, int level = 0) const;

    GLuint id() const noexcept { return name_.get(); }
    GLenum target() const noexcept { return desc_.target; }
    GLenum internalFormat() const noexcept { return desc_.internalFormat; }
    int width() const noexcept { return desc_.width; }
    int height() const noexcept { return desc_.height; }
    int layers() const noexcept { return desc_.layers; }
    int levels() const noexcept { return desc_.levels; }
    // Bytes of storage (all levels and layers), from the internal format; for memory figures.
    std::size_t byteSize() const noexcept;

private:
    GlName<TextureDeleter> name_;
    TextureDesc desc_;
};

// Bytes per texel of a sized internal format; 0 for formats strata does not know.
std::size_t bytesPerTexel(GLenum internalFormat) noexcept;

}  // namespace strata::gpu
