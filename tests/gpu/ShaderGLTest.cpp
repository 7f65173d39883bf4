#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "strata/gpu/Check.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"

using namespace strata;

namespace {

std::string compileError(const gpu::StageSource& stage) {
    try {
        gpu::Program program("broken", std::vector<gpu::StageSource>{stage});
    } catch (const Error& e) {
        return e.what();
    }
    return "<compiled>";
}

}  // namespace

TEST(Program, CompileErrorNamesTheFileAndLine) {
    gpu::Context context;
    // Line 4 of the file uses an undeclared name.
    const std::string text =
        "layout(location = 0) out vec4 colour;\n"  // 1
        "void main() {\n"                          // 2
        "    float x = 1.0;\n"                     // 3
        "    colour = vec4(idTex, x, 0, 1);\n"     // 4
        "}\n";
    const std::string what = compileError(gpu::assembleStage("csg/evaluate.frag", text));
    EXPECT_EQ(what.rfind("shaders/csg/evaluate.frag:4: ", 0), 0u) << what;
    EXPECT_NE(what.find("idTex"), std::string::npos) << what;
}

TEST(Program, LineNumbersSurviveDefinesAndIncludes) {
    gpu::Context context;
    // The include expands to several lines and the defines add more; the error
    // on line 6 of this file must still be reported as line 6.
    const std::string text =
        "#include \"common/fullscreen.glsl\"\n"  // 1
        "layout(location = 0) out vec4 colour;\n"  // 2
        "void main() {\n"                          // 3
        "    vec2 p = fullscreenPosition(0);\n"    // 4
        "    colour = vec4(p, SCALE, 1.0);\n"      // 5
        "    colour.x += undeclaredThing;\n"       // 6
        "}\n";
    const auto stage = gpu::assembleStage("test/lines.frag", text, {{"SCALE", "2.0"}, {"UNUSED", ""}});
    const std::string what = compileError(stage);
    EXPECT_EQ(what.rfind("shaders/test/lines.frag:6: ", 0), 0u) << what;
    EXPECT_NE(what.find("undeclaredThing"), std::string::npos) << what;
}

TEST(Program, LinkErrorNamesTheStages) {
    gpu::Context context;
    // The fragment stage reads an input the vertex stage never writes.
    const auto vert = gpu::loadStage("common/fullscreen.vert");
    const auto frag = gpu::assembleStage("test/link.frag",
                                         "layout(location = 3) in vec4 missing;\n"
                                         "layout(location = 0) out vec4 c;\n"
                                         "void main() { c = missing; }\n");
    try {
        gpu::Program program("link", std::vector<gpu::StageSource>{vert, frag});
        // Some drivers link this (the input reads as undefined); that is allowed.
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("shaders/common/fullscreen.vert + shaders/test/link.frag: link failed"),
                  std::string::npos)
            << what;
    }
}

TEST(Program, FullscreenPassFillsEveryPixel) {
    gpu::Context context;
    constexpr int kW = 9, kH = 6;
    gpu::Texture target = gpu::Texture::create2D("target", GL_RG32F, kW, kH);
    gpu::Framebuffer framebuffer("fullscreen");
    framebuffer.attachTexture(GL_COLOR_ATTACHMENT0, target);
    framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    framebuffer.checkComplete();

    // Writes the pixel centre scaled by a uniform: checks vUv, gl_FragCoord, uniforms and defines.
    const auto frag = gpu::assembleStage("test/uv.frag",
                                         "layout(location = 0) in vec2 vUv;\n"
                                         "layout(location = 0) out vec2 result;\n"
                                         "uniform float uScale;\n"
                                         "void main() { result = vec2(vUv.x * float(WIDTH), gl_FragCoord.y) * uScale; }\n",
                                         {{"WIDTH", std::to_string(kW)}});
    gpu::Program program("uv", std::vector<gpu::StageSource>{gpu::loadStage("common/fullscreen.vert"), frag});
    program.setUniform("uScale", 2.0f);
    gpu::VertexArray empty("empty");

    framebuffer.bindForDraw();
    glViewport(0, 0, kW, kH);
    program.use();
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gpu::checkErrors();

    std::vector<float> texels(kW * kH * 2);
    target.download(GL_RG, GL_FLOAT, std::as_writable_bytes(std::span(texels)));
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const float* t = &texels[(y * kW + x) * 2];
            EXPECT_NEAR(t[0], 2.0f * (x + 0.5f), 1e-4f) << x << "," << y;
            EXPECT_NEAR(t[1], 2.0f * (y + 0.5f), 1e-4f) << x << "," << y;
        }
    }
    gpu::Framebuffer::bindDefault();
}
