#include "NormalPass.h"

#include <algorithm>

#include "EvaluatePass.h"
#include "ShaderInterface.h"
#include "ShadePass.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Per tree leaf: whether the stencil marks in its rectangle within `tile`
// are its own, that is, no other leaf holding its mark slot this frame
// (`markLeaves`, screen rectangles `markRects`) meets that rectangle (the
// evaluator writes a leaf only inside its rectangle, as this pass draws it
// only there). 0 for leaves that hold no slot. A slot shared by more than
// kMaxPairwise leaves is not looked into (its leaves count as not owning
// their marks, which is always safe: they take the checked shader), so the
// test stays linear in the leaves however many there are.
constexpr std::size_t kMaxPairwise = 128;

std::vector<char> marksOwnedInRect(const FrameTargets& targets, std::span<const int> markLeaves,
                                   std::span<const PixelRect> markRects, const PixelRect& tile) {
    std::vector<std::vector<std::size_t>> bySlot(FrameTargets::kMarkSlots);
    int most = -1;
    for (std::size_t k = 0; k < markLeaves.size(); ++k) {
        bySlot[static_cast<std::size_t>(targets.markSlot(markLeaves[k]))].push_back(k);
        most = std::max(most, markLeaves[k]);
    }
    std::vector<char> owned(markLeaves.size(), 1);
    for (const std::vector<std::size_t>& sharing : bySlot) {
        if (sharing.size() > kMaxPairwise) {
            for (std::size_t k : sharing) owned[k] = 0;
            continue;
        }
        for (std::size_t i = 0; i < sharing.size(); ++i) {
            const PixelRect r = markRects[sharing[i]].intersection(tile);
            for (std::size_t j = i + 1; j < sharing.size(); ++j) {
                if (markRects[sharing[j]].intersection(tile).intersects(r)) owned[sharing[i]] = owned[sharing[j]] = 0;
            }
        }
    }
    std::vector<char> byLeaf(static_cast<std::size_t>(most + 1), 0);
    for (std::size_t k = 0; k < markLeaves.size(); ++k) byLeaf[static_cast<std::size_t>(markLeaves[k])] = owned[k];
    return byLeaf;
}

}  // namespace

NormalPass::NormalPass() = default;

gpu::Program& NormalPass::program(bool trusted, const std::optional<Lighting>& litAs) {
    const std::size_t shading = !litAs ? 0 : *litAs == Lighting::Strata ? 1 : 2;
    std::optional<gpu::Program>& slot = programs_[shading][trusted ? 1 : 0];
    if (!slot) {
        std::vector<gpu::ShaderDefine> defines{{"FACE_NORMAL", "1"}};
        if (trusted) defines.push_back({"TRUST_MARKS", "1"});
        if (shading > 0) defines.push_back({"LIT", "1"});
        if (shading == 2) defines.push_back({"OPENSCAD_LIGHT", "1"});
        slot.emplace(gpu::Program::fromFiles(trusted ? "normal (trusting marks)" : "normal",
                                             {"csg/surface.vert", "csg/normal.frag"}, defines));
    }
    return *slot;
}

void NormalPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
                     const csg::CompiledTree& tree, const std::vector<PixelRect>& rects,
                     const std::vector<std::uint32_t>& shownFaces, const std::vector<glm::vec2>& baseColors,
                     std::span<const int> markLeaves, std::span<const PixelRect> markRects,
                     const std::optional<Lighting>& litAs) {
    gpu::Program& checked = program(false, litAs);
    gpu::Program& trusted = program(true, litAs);
    for (gpu::Program* p : {&checked, &trusted}) {
        setSurfaceView(*p, view);
        if (litAs) ShadePass::setLight(*p, view, *litAs);
    }
    // The peel drew a tile other than the frame's corner one through an
    // offset viewport (PeelPass::beginPasses), which rounds window positions
    // a little apart from this pass's: a sixteenth of the depth's change
    // across a pixel covers that on faces seen nearly edge on
    // (shaders/csg/normal.frag). At 1024 x 768 a 256th left 63 pixels of
    // OpenSCAD's GEB example without their normal.
    const bool offset = tile.x != 0 || tile.y != 0;
    checked.setUniform(shader::kNormalSlack, offset ? 0.0625f : 0.0f);
    const std::vector<char> ownMarks =
        targets.leafMarks ? marksOwnedInRect(targets, markLeaves, markRects, tile) : std::vector<char>{};
    auto ownsMarks = [&](int leaf) {
        return static_cast<std::size_t>(leaf) < ownMarks.size() && ownMarks[static_cast<std::size_t>(leaf)];
    };
    const gpu::Program* inUse = nullptr;
    targets.resultDepth.bindUnit(shader::kTextureResultDepth);
    targets.resultLeaf.bindUnit(shader::kTextureResultLeaf);
    (litAs ? targets.shadeTarget() : targets.normalFramebuffer()).bindForDraw();
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    scene.vertexArray().bind();
    for (std::size_t k = 0; k < tree.operandLeaf.size(); ++k) {
        const PixelRect r = rects[k].intersection(tile);
        if (r.empty()) continue;
        glScissor(r.x, r.y, r.width, r.height);
        // A group's members are leaves of their own here: the evaluator
        // wrote the member that makes each surface (EvaluatePass.h).
        for (const int leaf : tree.leavesOf(k)) {
            const std::uint32_t shown = shownFaces[static_cast<std::size_t>(leaf)];
            if (shown == 0 || scene.leaf(leaf).indexCount == 0) continue;
            gpu::Program& program = ownsMarks(leaf) && scene.leaf(leaf).convex ? trusted : checked;
            if (&program != inUse) {
                program.use();
                inUse = &program;
            }
            program.setUniform(shader::kNormalLeaf, leaf);
            if (&program == &checked) program.setUniform(shader::kNormalConvex, scene.leaf(leaf).convex ? 1 : 0);
            program.setUniform(shader::kNormalBaseColor, baseColors[static_cast<std::size_t>(leaf)]);
            // Marks tell flips apart: a draw per flip the leaf shows. One mark for
            // all does not: one draw, and the shader reads the flip.
            for (int flip = 0; flip < (targets.leafMarks ? 2 : 1); ++flip) {
                constexpr std::uint32_t kBoth = EvaluatePass::kFrontFaces | EvaluatePass::kBackFaces;
                const std::uint32_t faces = targets.leafMarks ? (shown >> (flip * EvaluatePass::kFlipped)) & kBoth
                                                              : (shown | shown >> EvaluatePass::kFlipped) & kBoth;
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
                if (&program == &trusted) program.setUniform(shader::kNormalFlip, flip);
                scene.drawLeaf(leaf);
            }
        }
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
