#include "NormalPass.h"

#include <algorithm>

#include "EvaluatePass.h"

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/surface.vert and normal.frag.
constexpr GLint kViewProjection = 0;
constexpr GLint kEye = 1;
constexpr GLint kForward = 2;
constexpr GLint kLeaf = 3;
constexpr GLint kBaseColor = 5;
constexpr GLint kFlip = 6;  // TRUST_MARKS only
constexpr GLint kMember = 7;  // GROUP only
constexpr GLint kSlack = 8;   // GROUP only

// Per operand k: whether the stencil marks in its rectangle within `tile`
// are its own, that is, no other operand with k's mark slot meets that
// rectangle (the evaluator writes an operand's leaf only inside its
// rectangle, as this pass draws it only there).
std::vector<char> marksOwnedInRect(const FrameTargets& targets, const std::vector<int>& operandLeaves,
                                   const std::vector<PixelRect>& rects, const PixelRect& tile) {
    std::vector<std::vector<std::size_t>> bySlot(FrameTargets::kMarkSlots);
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        bySlot[static_cast<std::size_t>(targets.markSlot(operandLeaves[k]))].push_back(k);
    }
    std::vector<char> owned(operandLeaves.size(), 1);
    for (const std::vector<std::size_t>& sharing : bySlot) {
        for (std::size_t i = 0; i < sharing.size(); ++i) {
            const PixelRect r = rects[sharing[i]].intersection(tile);
            for (std::size_t j = i + 1; j < sharing.size(); ++j) {
                if (rects[sharing[j]].intersection(tile).intersects(r)) owned[sharing[i]] = owned[sharing[j]] = 0;
            }
        }
    }
    return owned;
}

}  // namespace

NormalPass::NormalPass()
    : checked_(gpu::Program::fromFiles("normal", {"csg/surface.vert", "csg/normal.frag"}, {{"FACE_NORMAL", "1"}})),
      trusted_(gpu::Program::fromFiles("normal (trusting marks)", {"csg/surface.vert", "csg/normal.frag"},
                                       {{"FACE_NORMAL", "1"}, {"TRUST_MARKS", "1"}})),
      grouped_(gpu::Program::fromFiles("normal (group members)", {"csg/surface.vert", "csg/normal.frag"},
                                       {{"FACE_NORMAL", "1"}, {"GROUP", "1"}})) {}

void NormalPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
                     const std::vector<int>& operandLeaves, const std::vector<PixelRect>& rects,
                     const std::vector<std::uint32_t>& shownFaces, const std::vector<glm::vec2>& baseColors,
                     const std::vector<std::vector<int>>& groups) {
    for (gpu::Program* program : {&checked_, &trusted_, &grouped_}) {
        program->setUniform(kViewProjection, view.viewProjection);
        program->setUniform(kEye, view.eye);
        program->setUniform(kForward, view.forward);
    }
    const std::vector<char> ownMarks =
        targets.leafMarks ? marksOwnedInRect(targets, operandLeaves, rects, tile) : std::vector<char>(operandLeaves.size(), 0);
    const gpu::Program* inUse = nullptr;
    targets.resultDepth.bindUnit(0);
    targets.resultLeaf.bindUnit(1);
    targets.normalTarget.bindForDraw();
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    scene.flatVertexArray().bind();
    // Draws `drawn` once per flip that operand leaf `leaf` shows, with that
    // leaf's marks, culling the faces it does not show.
    auto drawShown = [&](gpu::Program& program, int leaf, std::uint32_t shown, int drawn) {
        // Marks tell flips apart: a draw per flip the leaf shows. One mark for
        // all does not: one draw, and the shader reads the flip.
        for (int flip = 0; flip < (targets.leafMarks ? 2 : 1); ++flip) {
            const std::uint32_t faces = targets.leafMarks ? (shown >> (flip * EvaluatePass::kFlipped)) & 3u
                                                          : (shown | shown >> EvaluatePass::kFlipped) & 3u;
            if (faces == 0) continue;
            // Faces the result does not show here are culled before rasterizing.
            if (faces == EvaluatePass::kFrontFaces || faces == EvaluatePass::kBackFaces) {
                glEnable(GL_CULL_FACE);
                glCullFace(faces == EvaluatePass::kFrontFaces ? GL_BACK : GL_FRONT);
            } else {
                glDisable(GL_CULL_FACE);
            }
            glStencilFuncSeparate(GL_FRONT, GL_EQUAL, targets.mark(leaf, false, flip != 0), 0xff);
            glStencilFuncSeparate(GL_BACK, GL_EQUAL, targets.mark(leaf, true, flip != 0), 0xff);
            if (&program == &trusted_) program.setUniform(kFlip, flip);
            scene.drawLeaf(drawn);
        }
    };
    auto isGroup = [&](std::size_t k) { return k < groups.size() && groups[k].size() > 1; };
    bool anyGroup = false;
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        const int leaf = operandLeaves[k];
        const PixelRect r = rects[k].intersection(tile);
        const std::uint32_t shown = shownFaces[static_cast<std::size_t>(leaf)];
        if (r.empty() || shown == 0 || scene.leaf(leaf).indexCount == 0) continue;
        if (isGroup(k)) {
            anyGroup = true;
            continue;
        }
        glScissor(r.x, r.y, r.width, r.height);
        gpu::Program& program = ownMarks[k] && scene.leaf(leaf).convex ? trusted_ : checked_;
        if (&program != inUse) {
            program.use();
            inUse = &program;
        }
        program.setUniform(kLeaf, leaf);
        program.setUniform(kBaseColor, baseColors[static_cast<std::size_t>(leaf)]);
        drawShown(program, leaf, shown, leaf);
    }
    if (anyGroup) {
        // Groups' members write the leaf image too: they read a copy of it.
        if (!leafCopy_.id() || leafCopy_.width() != view.width || leafCopy_.height() != view.height) {
            leafCopy_ = gpu::Texture::create2D("result leaf copy", GL_R32I, view.width, view.height);
        }
        for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
            const PixelRect r = rects[k].intersection(tile);
            if (!isGroup(k) || r.empty()) continue;
            glCopyImageSubData(targets.resultLeaf.id(), GL_TEXTURE_2D, 0, r.x, r.y, 0, leafCopy_.id(), GL_TEXTURE_2D,
                               0, r.x, r.y, 0, r.width, r.height, 1);
        }
        leafCopy_.bindUnit(1);
        targets.groupNormalTarget.bindForDraw();
        grouped_.use();
        grouped_.setUniform(kSlack, static_cast<float>(1e-6 * view.farPlane));
        for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
            const int leaf = operandLeaves[k];
            const PixelRect r = rects[k].intersection(tile);
            const std::uint32_t shown = shownFaces[static_cast<std::size_t>(leaf)];
            if (!isGroup(k) || r.empty() || shown == 0) continue;
            glScissor(r.x, r.y, r.width, r.height);
            grouped_.setUniform(kLeaf, leaf);
            for (auto member = groups[k].rbegin(); member != groups[k].rend(); ++member) {
                grouped_.setUniform(kMember, *member);
                grouped_.setUniform(kBaseColor, baseColors[static_cast<std::size_t>(*member)]);
                drawShown(grouped_, leaf, shown, *member);
            }
        }
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
