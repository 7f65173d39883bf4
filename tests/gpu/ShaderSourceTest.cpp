#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "strata/core/Error.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/ShaderSource.h"

using namespace strata;

TEST(ShaderSource, EmbeddedFilesIncludeTheCommonCode) {
    EXPECT_TRUE(gpu::hasEmbeddedShader("common/fullscreen.vert"));
    EXPECT_TRUE(gpu::hasEmbeddedShader("common/fullscreen.glsl"));
    EXPECT_FALSE(gpu::hasEmbeddedShader("common/nope.glsl"));
    EXPECT_NE(gpu::embeddedShader("common/fullscreen.glsl").find("fullscreenPosition"), std::string_view::npos);
    EXPECT_THROW(gpu::embeddedShader("common/nope.glsl"), Error);

    const auto files = gpu::embeddedShaderFiles();
    for (std::size_t i = 1; i < files.size(); ++i) EXPECT_LT(files[i - 1].path, files[i].path);
}

TEST(ShaderSource, StageComesFromTheExtension) {
    EXPECT_EQ(gpu::stageFromPath("csg/evaluate.frag"), static_cast<GLenum>(GL_FRAGMENT_SHADER));
    EXPECT_EQ(gpu::stageFromPath("a.vert"), static_cast<GLenum>(GL_VERTEX_SHADER));
    EXPECT_EQ(gpu::stageFromPath("a.geom"), static_cast<GLenum>(GL_GEOMETRY_SHADER));
    EXPECT_EQ(gpu::stageFromPath("a.comp"), static_cast<GLenum>(GL_COMPUTE_SHADER));
    EXPECT_THROW(gpu::stageFromPath("common/fullscreen.glsl"), Error);
}

TEST(ShaderSource, AssemblesVersionDefinesAndLineDirectives) {
    const auto stage = gpu::assembleStage("test/a.frag", "void main() {}\n", {{"LAYERS", "4"}, {"FAST", ""}});
    EXPECT_EQ(stage.stage, static_cast<GLenum>(GL_FRAGMENT_SHADER));
    EXPECT_EQ(stage.text,
              "#version 450 core\n"
              "#line 1 1\n"
              "#define LAYERS 4\n"
              "#define FAST\n"
              "#line 1 0\n"
              "void main() {}\n");
    ASSERT_GE(stage.sourceNames.size(), 1u);
    EXPECT_EQ(stage.sourceNames[0], "test/a.frag");
}

TEST(ShaderSource, IncludeIsExpandedOnceWithItsOwnSourceNumber) {
    const std::string text =
        "#extension GL_ARB_shader_viewport_layer_array : require\n"  // 1
        "#include \"common/fullscreen.glsl\"\n"                      // 2
        "  #  include \"common/fullscreen.glsl\"  // again: skipped\n"  // 3
        "void main() {}\n";                                           // 4
    const auto stage = gpu::assembleStage("test/b.vert", text);
    const std::string body(gpu::embeddedShader("common/fullscreen.glsl"));
    ASSERT_EQ(stage.sourceNames.size(), 3u);
    EXPECT_EQ(stage.sourceNames[2], "common/fullscreen.glsl");
    std::string expected =
        "#version 450 core\n"
        "#line 1 0\n"
        "#extension GL_ARB_shader_viewport_layer_array : require\n"
        "#line 1 2\n" +
        body + (body.ends_with("\n") ? "" : "\n") +
        "#line 3 0\n"
        "#line 4 0\n"
        "void main() {}\n";
    EXPECT_EQ(stage.text, expected);
}

TEST(ShaderSource, MissingIncludeNamesTheFileAndLine) {
    try {
        gpu::assembleStage("csg/evaluate.frag", "// first\n\n#include \"common/missing.glsl\"\n");
        FAIL() << "a missing include was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(),
                     "shaders/csg/evaluate.frag:3: #include \"common/missing.glsl\": no such file under shaders/");
    }
}

TEST(ShaderLog, MesaNvidiaAndGlslangLinesMapToFiles) {
    const std::vector<std::string> names{"csg/evaluate.frag", "csg/evaluate.frag (#defines)", "common/tree.glsl"};
    EXPECT_EQ(gpu::formatShaderLog("0:27(5): error: `idTex' undeclared\n", names, "csg/evaluate.frag"),
              "shaders/csg/evaluate.frag:27: error: `idTex' undeclared");
    EXPECT_EQ(gpu::formatShaderLog("2:12(1): error: syntax error\n0:3(9): warning: unused\n", names, "x"),
              "shaders/common/tree.glsl:12: error: syntax error\nshaders/csg/evaluate.frag:3: warning: unused");
    EXPECT_EQ(gpu::formatShaderLog("0(27) : error C1008: undefined variable \"idTex\"", names, "x"),
              "shaders/csg/evaluate.frag:27: error C1008: undefined variable \"idTex\"");
    EXPECT_EQ(gpu::formatShaderLog("ERROR: 2:8: 'x' : undeclared identifier\n", names, "x"),
              "shaders/common/tree.glsl:8: error: 'x' : undeclared identifier");
    // A source number the stage does not have, and a line with no position.
    EXPECT_EQ(gpu::formatShaderLog("9:1(1): error: odd\n\nsomething else\n", names, "csg/evaluate.frag"),
              "shaders/csg/evaluate.frag:1: error: odd\nshaders/csg/evaluate.frag: something else");
}
