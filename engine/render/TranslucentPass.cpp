#include "TranslucentPass.h"

#include <glm/geometric.hpp>

#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

TranslucentPass::TranslucentPass()
    : program_(gpu::Program::fromFiles("translucent", {"csg/surface.vert", "csg/translucent.frag"},
                                       {{"FACE_NORMAL", "1"}})) {}

void TranslucentPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
                          const std::vector<TranslucentLeaf>& leaves) {
    if (leaves.empty()) return;
    setSurfaceView(program_, view);
    program_.setUniform(shader::kTranslucentToLight, glm::normalize(-view.forward + 0.25f * (view.up - view.right)));
    program_.use();
    targets.resultDepth.bindUnit(shader::kTextureResultDepth);
    targets.colorTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keep the image opaque
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    scene.vertexArray().bind();
    for (const TranslucentLeaf& t : leaves) {
        program_.setUniform(shader::kTranslucentColor, t.color);
        scene.drawLeaf(t.leaf);
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    gpu::checkErrors();
}

}  // namespace strata::render
