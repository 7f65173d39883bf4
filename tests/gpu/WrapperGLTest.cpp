#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/gpu/Buffer.h"
#include "strata/gpu/Check.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Query.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"

using namespace strata;

namespace {

std::string labelOf(GLenum identifier, GLuint id) {
    char label[64] = {};
    GLsizei length = 0;
    glGetObjectLabel(identifier, id, sizeof label, &length, label);
    return std::string(label, static_cast<std::size_t>(length));
}

// A moved-from wrapper holds 0; the moved-to one holds the object, still alive.
template <class T, class Make, class IsAlive>
void checkMove(Make make, IsAlive isAlive) {
    T a = make();
    const GLuint id = a.id();
    ASSERT_NE(id, 0u);
    T b(std::move(a));
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): that is the point
    EXPECT_EQ(b.id(), id);
    EXPECT_TRUE(isAlive(id));

    T c;
    EXPECT_EQ(c.id(), 0u);
    c = std::move(b);
    EXPECT_EQ(c.id(), id);
    EXPECT_EQ(b.id(), 0u);  // NOLINT(bugprone-use-after-move)

    // Move-assigning over a live object deletes the old one.
    T d = make();
    const GLuint other = d.id();
    d = std::move(c);
    EXPECT_EQ(d.id(), id);
    { T sink(std::move(c)); }  // c holds `other` after the swap; sink deletes it
    EXPECT_FALSE(isAlive(other));
}

}  // namespace

TEST(GlWrappers, MovedFromBufferHoldsZero) {
    gpu::Context context;
    checkMove<gpu::Buffer>([] { return gpu::Buffer("test buffer", 64); },
                           [](GLuint id) { return glIsBuffer(id) == GL_TRUE; });
    EXPECT_NO_THROW(gpu::checkErrors());
}

TEST(GlWrappers, MovedFromTextureHoldsZero) {
    gpu::Context context;
    checkMove<gpu::Texture>([] { return gpu::Texture::create2D("test texture", GL_RGBA8, 4, 4); },
                            [](GLuint id) { return glIsTexture(id) == GL_TRUE; });
}

TEST(GlWrappers, MovedFromFramebufferHoldsZero) {
    gpu::Context context;
    checkMove<gpu::Framebuffer>([] { return gpu::Framebuffer("test framebuffer"); },
                                [](GLuint id) { return glIsFramebuffer(id) == GL_TRUE; });
}

TEST(GlWrappers, MovedFromQueryAndVertexArrayHoldZero) {
    gpu::Context context;
    checkMove<gpu::Query>([] { return gpu::Query("test query", GL_ANY_SAMPLES_PASSED); },
                          [](GLuint id) { return glIsQuery(id) == GL_TRUE; });
    checkMove<gpu::VertexArray>([] { return gpu::VertexArray("test vao"); },
                                [](GLuint id) { return glIsVertexArray(id) == GL_TRUE; });
}

TEST(GlWrappers, EveryObjectIsLabelled) {
    gpu::Context context;
    gpu::Buffer buffer("depth layers", 16);
    gpu::Texture texture = gpu::Texture::create2DArray("peel layers", GL_RG32F, 8, 8, 3);
    gpu::Framebuffer framebuffer("peel target");
    gpu::Query query("peel drawn", GL_ANY_SAMPLES_PASSED);
    gpu::VertexArray vao("fullscreen");
    EXPECT_EQ(labelOf(GL_BUFFER, buffer.id()), "depth layers");
    EXPECT_EQ(labelOf(GL_TEXTURE, texture.id()), "peel layers");
    EXPECT_EQ(labelOf(GL_FRAMEBUFFER, framebuffer.id()), "peel target");
    EXPECT_EQ(labelOf(GL_QUERY, query.id()), "peel drawn");
    EXPECT_EQ(labelOf(GL_VERTEX_ARRAY, vao.id()), "fullscreen");
}

TEST(Buffer, UploadThenDownloadRoundTrips) {
    gpu::Context context;
    const std::vector<std::uint32_t> data{1, 2, 3, 0xdeadbeef};
    gpu::Buffer buffer = gpu::Buffer::fromSpan<std::uint32_t>("round trip", data);
    EXPECT_EQ(buffer.size(), 16u);
    const std::array<std::uint32_t, 2> patch{7, 8};
    buffer.uploadSpan<std::uint32_t>(patch, 4);
    std::vector<std::uint32_t> back(4);
    buffer.downloadSpan<std::uint32_t>(back);
    EXPECT_EQ(back, (std::vector<std::uint32_t>{1, 7, 8, 0xdeadbeef}));
    buffer.clearToZero();
    buffer.downloadSpan<std::uint32_t>(back);
    EXPECT_EQ(back, (std::vector<std::uint32_t>{0, 0, 0, 0}));
    EXPECT_THROW(buffer.uploadSpan<std::uint32_t>(data, 4), Error);  // past the end
    EXPECT_NO_THROW(gpu::checkErrors());
}

TEST(Texture, ReportsItsStorageSize) {
    gpu::Context context;
    gpu::Texture layers = gpu::Texture::create2DArray("layers", GL_RG32F, 16, 8, 5);
    EXPECT_EQ(layers.byteSize(), 16u * 8u * 5u * 8u);
    EXPECT_EQ(layers.layers(), 5);
    EXPECT_THROW(gpu::Texture::create2D("empty", GL_RGBA8, 0, 4), Error);
}

TEST(Framebuffer, IncompleteFramebufferThrowsNamingTheStatusAndTheCaller) {
    gpu::Context context;
    gpu::Framebuffer framebuffer("nothing attached");
    const int line = __LINE__ + 2;
    try {
        framebuffer.checkComplete();
        FAIL() << "an empty framebuffer passed checkComplete";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what, "tests/gpu/WrapperGLTest.cpp:" + std::to_string(line) +
                            ": incomplete framebuffer 'nothing attached' "
                            "(GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT)");
    }
}

TEST(Framebuffer, MismatchedAttachmentIsIncomplete) {
    gpu::Context context;
    // A depth format on a colour attachment is not colour-renderable.
    gpu::Texture depth = gpu::Texture::create2D("depth", GL_DEPTH_COMPONENT32F, 4, 4);
    gpu::Framebuffer framebuffer("depth as colour");
    framebuffer.attachTexture(GL_COLOR_ATTACHMENT0, depth);
    framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    EXPECT_EQ(framebuffer.status(), static_cast<GLenum>(GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT));
    EXPECT_THROW(framebuffer.checkComplete(), Error);
    glGetError();
}

TEST(Framebuffer, ClearThenReadBackRoundTrips) {
    gpu::Context context;
    constexpr int kW = 7, kH = 5;  // odd sizes catch row-alignment mistakes
    gpu::Texture colour = gpu::Texture::create2D("colour", GL_RGBA8, kW, kH);
    gpu::Texture value = gpu::Texture::create2D("value", GL_R32F, kW, kH);
    gpu::Framebuffer framebuffer("clear target");
    framebuffer.attachTexture(GL_COLOR_ATTACHMENT0, colour);
    framebuffer.attachTexture(GL_COLOR_ATTACHMENT1, value);
    framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
    ASSERT_NO_THROW(framebuffer.checkComplete());

    const float rgba[4] = {1.0f, 0.5f, 0.0f, 1.0f};
    const float z[4] = {-2.75f, 0, 0, 0};
    framebuffer.clearColor(0, rgba);
    framebuffer.clearColor(1, z);

    std::vector<std::uint8_t> pixels(kW * kH * 4);
    colour.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(pixels)));
    for (int i = 0; i < kW * kH; ++i) {
        EXPECT_EQ(pixels[i * 4 + 0], 255);
        EXPECT_EQ(pixels[i * 4 + 1], 128);  // 0.5 * 255 = 127.5, rounded to nearest
        EXPECT_EQ(pixels[i * 4 + 2], 0);
        EXPECT_EQ(pixels[i * 4 + 3], 255);
    }
    std::vector<float> values(kW * kH);
    value.download(GL_RED, GL_FLOAT, std::as_writable_bytes(std::span(values)));
    for (float v : values) EXPECT_EQ(v, -2.75f);

    // glReadPixels through the read binding gives the same.
    framebuffer.bindForRead();
    framebuffer.setReadBuffer(GL_COLOR_ATTACHMENT1);
    float one = 0;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(3, 2, 1, 1, GL_RED, GL_FLOAT, &one);
    EXPECT_EQ(one, -2.75f);
    EXPECT_NO_THROW(gpu::checkErrors());
}

TEST(Texture, ArrayLayersAreSeparate) {
    gpu::Context context;
    constexpr int kW = 3, kH = 2, kLayers = 4;
    gpu::Texture layers = gpu::Texture::create2DArray("layers", GL_R32F, kW, kH, kLayers);
    gpu::Framebuffer framebuffer("one layer");
    for (int layer = 0; layer < kLayers; ++layer) {
        framebuffer.attachLayer(GL_COLOR_ATTACHMENT0, layers, layer);
        framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0});
        framebuffer.checkComplete();
        const float v[4] = {static_cast<float>(layer) + 0.25f, 0, 0, 0};
        framebuffer.clearColor(0, v);
    }
    std::vector<float> all(kW * kH * kLayers);
    layers.download(GL_RED, GL_FLOAT, std::as_writable_bytes(std::span(all)));
    for (int layer = 0; layer < kLayers; ++layer)
        for (int i = 0; i < kW * kH; ++i) EXPECT_EQ(all[layer * kW * kH + i], layer + 0.25f);

    std::vector<float> one(kW * kH);
    layers.downloadRegion(0, 0, 2, kW, kH, 1, GL_RED, GL_FLOAT, std::as_writable_bytes(std::span(one)));
    for (float v : one) EXPECT_EQ(v, 2.25f);
    EXPECT_NO_THROW(gpu::checkErrors());
}
