#include "strata/gpu/Texture.h"

#include <string>

#include "strata/gpu/Check.h"

namespace strata::gpu {

std::size_t bytesPerTexel(GLenum internalFormat) noexcept {
    switch (internalFormat) {
        case GL_R8: case GL_R8UI: case GL_R8I: case GL_STENCIL_INDEX8:
            return 1;
        case GL_R16F: case GL_R16UI: case GL_R16I: case GL_RG8: case GL_RG8UI: case GL_RG8I:
        case GL_DEPTH_COMPONENT16:
            return 2;
        case GL_DEPTH_COMPONENT24:
            return 3;  // drivers pad it to 4; this is the honest minimum
        case GL_R32F: case GL_R32UI: case GL_R32I: case GL_RG16F: case GL_RG16UI: case GL_RG16I:
        case GL_RGBA8: case GL_RGBA8UI: case GL_RGBA8I: case GL_SRGB8_ALPHA8: case GL_RGB10_A2:
        case GL_R11F_G11F_B10F: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8:
            return 4;
        case GL_DEPTH32F_STENCIL8:
            return 5;
        case GL_RG32F: case GL_RG32UI: case GL_RG32I: case GL_RGBA16F: case GL_RGBA16UI:
        case GL_RGBA16I: case GL_RGBA16:
            return 8;
        case GL_RGB32F: case GL_RGB32UI: case GL_RGB32I:
            return 12;
        case GL_RGBA32F: case GL_RGBA32UI: case GL_RGBA32I:
            return 16;
        default:
            return 0;
    }
}

Texture::Texture(std::string_view label, const TextureDesc& desc) : desc_(desc) {
    if (desc_.layers <= 0) desc_.layers = 1;
    if (desc_.levels <= 0) desc_.levels = 1;
    if (desc_.width <= 0 || desc_.height <= 0)
        fail("texture '" + std::string(label) + "' has size " + std::to_string(desc_.width) + "x" +
             std::to_string(desc_.height));
    if (desc_.target != GL_TEXTURE_2D && desc_.target != GL_TEXTURE_2D_ARRAY)
        fail("texture '" + std::string(label) + "': target " + enumName(desc_.target) +
             " is not GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY");
    if (desc_.target == GL_TEXTURE_2D) desc_.layers = 1;

    GLuint id = 0;
    glCreateTextures(desc_.target, 1, &id);
    name_ = GlName<TextureDeleter>(id);
    if (desc_.target == GL_TEXTURE_2D)
        glTextureStorage2D(id, desc_.levels, desc_.internalFormat, desc_.width, desc_.height);
    else
        glTextureStorage3D(id, desc_.levels, desc_.internalFormat, desc_.width, desc_.height, desc_.layers);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(desc_.minFilter));
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(desc_.magFilter));
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(desc_.wrap));
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(desc_.wrap));
    setLabel(GL_TEXTURE, id, label);
}

Texture Texture::create2D(std::string_view label, GLenum internalFormat, int width, int height) {
    TextureDesc desc;
    desc.internalFormat = internalFormat;
    desc.width = width;
    desc.height = height;
    return Texture(label, desc);
}

Texture Texture::create2DArray(std::string_view label, GLenum internalFormat, int width, int height,
                               int layers) {
    TextureDesc desc;
    desc.target = GL_TEXTURE_2D_ARRAY;
    desc.internalFormat = internalFormat;
    desc.width = width;
    desc.height = height;
    desc.layers = layers;
    return Texture(label, desc);
}

void Texture::bindUnit(GLuint unit) const { glBindTextureUnit(unit, id()); }

void Texture::bindImage(GLuint unit, GLenum access, int level) const {
    glBindImageTexture(unit, id(), level, desc_.target == GL_TEXTURE_2D_ARRAY ? GL_TRUE : GL_FALSE, 0,
                       access, desc_.internalFormat);
}

void Texture::clear(GLenum format, GLenum type, const void* value, int level) {
    glClearTexImage(id(), level, format, type, value);
}

void Texture::upload(int x, int y, int z, int width, int height, int depth, GLenum format, GLenum type,
                     const void* pixels, int level) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (desc_.target == GL_TEXTURE_2D)
        glTextureSubImage2D(id(), level, x, y, width, height, format, type, pixels);
    else
        glTextureSubImage3D(id(), level, x, y, z, width, height, depth, format, type, pixels);
}

void Texture::download(GLenum format, GLenum type, std::span<std::byte> out, int level) const {
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(id(), level, format, type, static_cast<GLsizei>(out.size()), out.data());
}

void Texture::downloadRegion(int x, int y, int z, int width, int height, int depth, GLenum format,
                             GLenum type, std::span<std::byte> out, int level) const {
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(id(), level, x, y, z, width, height, depth, format, type,
                         static_cast<GLsizei>(out.size()), out.data());
}

std::size_t Texture::byteSize() const noexcept {
    std::size_t total = 0;
    std::size_t w = static_cast<std::size_t>(desc_.width), h = static_cast<std::size_t>(desc_.height);
    for (int level = 0; level < desc_.levels; ++level) {
        total += w * h * static_cast<std::size_t>(desc_.layers) * bytesPerTexel(desc_.internalFormat);
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    return total;
}

}  // namespace strata::gpu
