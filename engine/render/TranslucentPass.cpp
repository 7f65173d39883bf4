#include "TranslucentPass.h"

#include <glm/geometric.hpp>

#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

TranslucentPass::TranslucentPass() = default;

gpu::Program& TranslucentPass::program(bool windowDepth) {
    std::optional<gpu::Program>& slot = programs_[windowDepth ? 1 : 0];
    if (!slot) {
        std::vector<gpu::ShaderDefine> defines{{"FACE_NORMAL", "1"}};
        if (windowDepth) defines.push_back({"WINDOW_DEPTH", "1"});
        slot.emplace(gpu::Program::fromFiles(windowDepth ? "translucent over a plain frame" : "translucent",
                                             {"csg/surface.vert", "csg/translucent.frag"}, defines));
    }
    return *slot;
}

void TranslucentPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
                          const std::vector<TranslucentLeaf>& leaves, const gpu::Texture* windowDepth) {
    if (leaves.empty()) return;
    gpu::Program& program = this->program(windowDepth != nullptr);
    setSurfaceView(program, view);
    program.setUniform(shader::kTranslucentToLight, glm::normalize(-view.forward + 0.25f * (view.up - view.right)));
    program.use();
    if (windowDepth != nullptr) {
        // The inverse of PlainPass::reversedDepth's unpulled terms.
        const auto nearPlane = static_cast<float>(view.nearPlane), farPlane = static_cast<float>(view.farPlane);
        program.setUniform(shader::kTranslucentFromWindow, view.orthographic
                                                               ? glm::vec3(0.0f, farPlane, farPlane - nearPlane)
                                                               : glm::vec3(nearPlane, 0.0f, 0.0f));
        windowDepth->bindUnit(shader::kTextureWindowDepth);
    } else {
        targets.resultDepth.bindUnit(shader::kTextureResultDepth);
    }
    targets.colorTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keep the image opaque
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    scene.vertexArray().bind();
    for (const TranslucentLeaf& t : leaves) {
        program.setUniform(shader::kTranslucentColor, t.color);
        scene.drawLeaf(t.leaf);
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    gpu::checkErrors();
}

}  // namespace strata::render
