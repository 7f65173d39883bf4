#include "ShadePass.h"

#include <algorithm>
#include <cmath>

#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

ShadePass::ShadePass() : empty_("shade") {}

glm::vec3 ShadePass::openScadToLight(const ViewSetup& view) {
    return glm::normalize(-view.right + view.up - view.forward);
}

void ShadePass::setLight(gpu::Program& program, const ViewSetup& view, Lighting lighting) {
    if (lighting == Lighting::OpenScad) {
        program.setUniform(shader::kLightToLight, openScadToLight(view));
        return;
    }
    program.setUniform(shader::kSurfaceForward, view.forward);
    program.setUniform(shader::kLightRight, view.right);
    program.setUniform(shader::kLightUp, view.up);
    program.setUniform(shader::kLightHalfExtent, view.halfExtent);
    program.setUniform(shader::kLightOrthographic, view.orthographic ? 1 : 0);
    program.setUniform(shader::kLightSize, glm::ivec2(view.width, view.height));
}

float ShadePass::packBaseColor(const glm::vec3& rgb) {
    auto byte = [](float c) { return static_cast<std::uint32_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    return static_cast<float>(1u + (byte(rgb.r) << 16 | byte(rgb.g) << 8 | byte(rgb.b)));
}

std::vector<glm::vec2> ShadePass::baseColors(const SceneBuffers& scene, const ColorScheme& scheme) {
    std::vector<glm::vec2> bases;
    bases.reserve(scene.leafColors().size());
    for (const glm::vec4& own : scene.leafColors()) {
        const bool has = own.a >= 0.0f;
        bases.emplace_back(packBaseColor(has ? glm::vec3(own) : glm::vec3(scheme.faceFront)),
                           packBaseColor(has ? glm::vec3(own) : glm::vec3(scheme.faceBack)));
    }
    return bases;
}

void ShadePass::run(FrameTargets& targets, const ViewSetup& view, const ColorScheme& scheme, Lighting lighting,
                    bool outline, const std::optional<PixelRect>& marked) {
    const bool openScad = lighting == Lighting::OpenScad;
    std::optional<gpu::Program>& slot = programs_[(openScad ? 2u : 0u) + (outline ? 1u : 0u)];
    if (!slot) {
        std::vector<gpu::ShaderDefine> defines;
        if (openScad) defines.push_back({"OPENSCAD_LIGHT", "1"});
        if (outline) defines.push_back({"OUTLINE", "1"});
        slot.emplace(gpu::Program::fromFiles("shade", {"common/fullscreen.vert", "csg/shade.frag"}, defines));
    }
    gpu::Program& program = *slot;
    program.setUniform(shader::kShadeBackground, scheme.background);
    setLight(program, view, lighting);
    program.use();
    targets.normal.bindUnit(shader::kTextureNormal);
    const gpu::Framebuffer& target = targets.shadeTarget();
    target.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    if (marked) {
        // The background everywhere, then the shader only where the evaluator wrote.
        const float background[4] = {scheme.background.r, scheme.background.g, scheme.background.b, 1.0f};
        glClearNamedFramebufferfv(target.id(), GL_COLOR, 0, background);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_NOTEQUAL, 0, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glEnable(GL_SCISSOR_TEST);
        glScissor(marked->x, marked->y, marked->width, marked->height);
    }
    empty_.bind();
    if (!marked || !marked->empty()) glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
