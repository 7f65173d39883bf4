#include "ShadePass.h"

#include <algorithm>
#include <cmath>

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/shade.frag.
constexpr GLint kBackground = 0;
constexpr GLint kForward = 3;
constexpr GLint kRight = 4;
constexpr GLint kUp = 5;
constexpr GLint kHalfExtent = 6;
constexpr GLint kOrthographic = 7;
constexpr GLint kSize = 8;

}  // namespace

ShadePass::ShadePass()
    : program_(gpu::Program::fromFiles("shade", {"common/fullscreen.vert", "csg/shade.frag"})), empty_("shade") {}

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

void ShadePass::run(FrameTargets& targets, const ViewSetup& view, const ColorScheme& scheme,
                    const std::optional<PixelRect>& marked) {
    program_.setUniform(kBackground, scheme.background);
    program_.setUniform(kForward, view.forward);
    program_.setUniform(kRight, view.right);
    program_.setUniform(kUp, view.up);
    program_.setUniform(kHalfExtent, view.halfExtent);
    program_.setUniform(kOrthographic, view.orthographic ? 1 : 0);
    program_.setUniform(kSize, glm::ivec2(view.width, view.height));
    program_.use();
    targets.normal.bindUnit(0);
    targets.colorTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    if (marked) {
        // The background everywhere, then the shader only where the evaluator wrote.
        const float background[4] = {scheme.background.r, scheme.background.g, scheme.background.b, 1.0f};
        targets.colorTarget.clearColor(0, background);
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
