#include "ShadePass.h"

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/shade.frag.
constexpr GLint kBackground = 0;
constexpr GLint kFaceFront = 1;
constexpr GLint kFaceBack = 2;
constexpr GLint kForward = 3;
constexpr GLint kRight = 4;
constexpr GLint kUp = 5;
constexpr GLint kHalfExtent = 6;
constexpr GLint kOrthographic = 7;
constexpr GLint kSize = 8;

}  // namespace

ShadePass::ShadePass()
    : program_(gpu::Program::fromFiles("shade", {"common/fullscreen.vert", "csg/shade.frag"})), empty_("shade") {}

void ShadePass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
                    const ColorScheme& scheme, bool markedOnly) {
    program_.setUniform(kBackground, scheme.background);
    program_.setUniform(kFaceFront, scheme.faceFront);
    program_.setUniform(kFaceBack, scheme.faceBack);
    program_.setUniform(kForward, view.forward);
    program_.setUniform(kRight, view.right);
    program_.setUniform(kUp, view.up);
    program_.setUniform(kHalfExtent, view.halfExtent);
    program_.setUniform(kOrthographic, view.orthographic ? 1 : 0);
    program_.setUniform(kSize, glm::ivec2(view.width, view.height));
    program_.use();
    targets.resultDepth.bindUnit(0);
    targets.resultLeaf.bindUnit(1);
    targets.normal.bindUnit(2);
    scene.leafColors().bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    targets.colorTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    if (markedOnly) {
        // The background everywhere, then the shader only where the evaluator wrote.
        const float background[4] = {scheme.background.r, scheme.background.g, scheme.background.b, 1.0f};
        targets.colorTarget.clearColor(0, background);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, FrameTargets::kWritten, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    empty_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_STENCIL_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
