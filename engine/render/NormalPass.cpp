#include "NormalPass.h"

#include "EvaluatePass.h"

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/surface.vert and normal.frag.
constexpr GLint kViewProjection = 0;
constexpr GLint kEye = 1;
constexpr GLint kForward = 2;
constexpr GLint kLeaf = 3;
constexpr GLint kFirstTriangle = 4;
constexpr GLint kBaseColor = 5;

}  // namespace

NormalPass::NormalPass() : program_(gpu::Program::fromFiles("normal", {"csg/surface.vert", "csg/normal.frag"})) {}

void NormalPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
                     const std::vector<int>& operandLeaves, const std::vector<PixelRect>& rects,
                     const std::vector<std::uint32_t>& shownFaces, const std::vector<glm::vec2>& baseColors) {
    program_.setUniform(kViewProjection, view.viewProjection);
    program_.setUniform(kEye, view.eye);
    program_.setUniform(kForward, view.forward);
    program_.use();
    targets.resultDepth.bindUnit(0);
    targets.resultLeaf.bindUnit(1);
    scene.faceNormals().bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    targets.normalTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    scene.vertexArray().bind();
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        const int leaf = operandLeaves[k];
        const PixelRect r = rects[k].intersection(tile);
        const std::uint32_t faces = shownFaces[static_cast<std::size_t>(leaf)];
        if (r.empty() || faces == 0 || scene.leaf(leaf).indexCount == 0) continue;
        // Faces the result does not show here are culled before rasterizing.
        if (faces == EvaluatePass::kFrontFaces || faces == EvaluatePass::kBackFaces) {
            glEnable(GL_CULL_FACE);
            glCullFace(faces == EvaluatePass::kFrontFaces ? GL_BACK : GL_FRONT);
        } else {
            glDisable(GL_CULL_FACE);
        }
        glScissor(r.x, r.y, r.width, r.height);
        glStencilFunc(GL_EQUAL, targets.mark(leaf), 0xff);
        program_.setUniform(kLeaf, leaf);
        program_.setUniform(kFirstTriangle, static_cast<int>(scene.leaf(leaf).firstTriangle));
        program_.setUniform(kBaseColor, baseColors[static_cast<std::size_t>(leaf)]);
        scene.drawLeaf(leaf);
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
