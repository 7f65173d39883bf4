#include "AlphaPass.h"

#include "ShadePass.h"
#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

AlphaPass::AlphaPass()
    : plain_(gpu::Program::fromFiles("alpha", {"common/fullscreen.vert", "csg/alpha.frag"})),
      empty_("alpha") {}

void AlphaPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
                    const ColorScheme& scheme, Lighting lighting, const std::vector<AlphaLeaf>& leaves) {
    if (leaves.empty()) return;
    bool anyAlone = false;
    for (const AlphaLeaf& a : leaves) anyAlone = anyAlone || a.alone;
    const bool openScad = lighting == Lighting::OpenScad;
    std::optional<gpu::Program>& slot = rears_[openScad ? 1 : 0];
    if (anyAlone && !slot) {
        std::vector<gpu::ShaderDefine> defines{{"FACE_NORMAL", "1"}, {"REAR", "1"}};
        if (openScad) defines.push_back({"OPENSCAD_LIGHT", "1"});
        slot.emplace(gpu::Program::fromFiles("alpha rear", {"csg/surface.vert", "csg/alpha.frag"}, defines));
    }
    gpu::Program* rear = anyAlone ? &*slot : nullptr;
    if (anyAlone) {
        if (depth_.width() != view.width || depth_.height() != view.height) {
            target_ = gpu::Framebuffer("alpha");
            depth_ = gpu::Texture::create2D("alpha depth", GL_DEPTH_COMPONENT32F, view.width, view.height);
            target_.attachTexture(GL_DEPTH_ATTACHMENT, depth_);
        }
        // The colour image is FrameTargets', which may have been made anew.
        target_.attachTexture(GL_COLOR_ATTACHMENT0, targets.color);
        target_.checkComplete();
        setSurfaceView(*rear, view);
        rear->setUniform(shader::kAlphaBackground, glm::vec3(scheme.background));
        ShadePass::setLight(*rear, view, lighting);
    }
    plain_.setUniform(shader::kAlphaBackground, glm::vec3(scheme.background));
    targets.resultLeaf.bindUnit(shader::kTextureResultLeaf);
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keep the image opaque
    for (const AlphaLeaf& a : leaves) {
        if (scene.leaf(a.leaf).indexCount == 0) continue;
        const PixelRect r = screenRect(view, scene.leafVertices(a.leaf));
        if (r.empty()) continue;
        glScissor(r.x, r.y, r.width, r.height);
        const int own = shader::leafCode(a.leaf, false), cut = shader::leafCode(a.leaf, true);
        if (a.alone) {
            // Its own surface: the nearest back face behind it. A depth-only
            // pass finds it, then the same program (so the same depths)
            // draws where the depth is equal: one fragment a pixel.
            target_.bindForDraw();
            glDepthMask(GL_TRUE);
            target_.clearDepth(1.0f);
            rear->setUniform(shader::kAlphaCodes, glm::ivec2(own, own));
            rear->setUniform(shader::kAlphaColor, a.color);
            rear->use();
            scene.vertexArray().bind();
            glEnable(GL_CULL_FACE);
            glCullFace(GL_FRONT);
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            scene.drawLeaf(a.leaf);
            glDepthFunc(GL_EQUAL);
            glDepthMask(GL_FALSE);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glEnable(GL_BLEND);
            scene.drawLeaf(a.leaf);
            glDisable(GL_BLEND);
            glDepthMask(GL_TRUE);
            glDepthFunc(GL_LESS);
            glDisable(GL_DEPTH_TEST);
            glCullFace(GL_BACK);
            glDisable(GL_CULL_FACE);
        }
        // The background behind: its cut faces, and its own surface unless alone.
        targets.colorTarget.bindForDraw();
        plain_.setUniform(shader::kAlphaCodes, glm::ivec2(cut, a.alone ? cut : own));
        plain_.setUniform(shader::kAlphaColor, a.color);
        plain_.use();
        empty_.bind();
        glEnable(GL_BLEND);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
    }
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
