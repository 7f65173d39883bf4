#include "PlainPass.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

gpu::Program plainProgram(bool ties) {
    std::vector<gpu::ShaderDefine> defines{{"FACE_NORMAL", "1"}, {"GROUP_MEMBERS", ""}, {"REVERSED_DEPTH", ""}};
    if (ties) defines.push_back({"TIE", ""});
    return gpu::Program::fromFiles(ties ? "plain ties" : "plain nearest", {"csg/surface.vert", "csg/plain.frag"},
                                   defines);
}

// Box comparisons mayTie may spend before it takes every leaf as one that
// may tie: a few tens of milliseconds, once per scene.
constexpr std::size_t kTieComparisons = std::size_t(1) << 25;

}  // namespace

PlainPass::PlainPass() : nearest_(plainProgram(false)), ties_(plainProgram(true)) {}

std::vector<int> PlainPass::plainLeaves(const csg::CompiledTree& compiled, const SceneBuffers& scene) {
    if (compiled.kind != csg::CompiledTree::Kind::Code) return {};
    for (std::uint32_t instruction : compiled.code) {
        const std::uint32_t op = instruction & csg::kOpMask;
        if ((instruction & csg::kOpNegate) || (op != csg::kOpPush && op != csg::kOpOr)) return {};
    }
    for (std::size_t k = 0; k < compiled.operandLeaf.size(); ++k) {
        if (compiled.leavesOf(k).size() != 1 || compiled.isUnionGroup(k)) return {};
        if (!scene.leaf(compiled.operandLeaf[k]).solidShells) return {};
    }
    if (scene.leaves().size() > SceneBuffers::kMostLeafNumbers) return {};
    return compiled.operandLeaf;
}

void PlainPass::setLeaves(const SceneBuffers& scene, std::vector<int> leaves) {
    leaves_ = std::move(leaves);
    const std::vector<DrawElementsIndirectCommand> commands = scene.leafCommands(leaves_);
    gpu::Buffer::uploadGrowing(nearestCommands_, "plain nearest commands", commands);
    nearestDraws_ = static_cast<GLsizei>(commands.size());
    tieMargin_ = -1.0;
    tieDraws_ = 0;
    tieCount_ = 0;
    uploadedColors_.clear();
}

std::vector<int> PlainPass::mayTie(const SceneBuffers& scene, std::span<const int> leaves, double margin,
                                   std::size_t budget) {
    // Sweep along x: leaves by the low end of their boxes, each compared
    // with those still open (whose high end reaches it).
    std::vector<int> order;
    order.reserve(leaves.size());
    for (int leaf : leaves)
        if (!scene.leaf(leaf).bounds.empty()) order.push_back(leaf);
    auto box = [&](int leaf) -> const geometry::Bounds& { return scene.leaf(leaf).bounds; };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return box(a).min.x < box(b).min.x; });
    std::vector<char> ties(scene.leaves().size(), 0);
    std::vector<int> open;
    std::size_t comparisons = 0;
    for (int leaf : order) {
        const geometry::Bounds& b = box(leaf);
        std::erase_if(open, [&](int other) { return box(other).max.x + margin < b.min.x - margin; });
        comparisons += open.size() + 1;
        if (comparisons > budget) {
            std::vector<int> all(leaves.begin(), leaves.end());
            std::sort(all.begin(), all.end());
            return all;
        }
        for (int other : open) {
            const geometry::Bounds& o = box(other);
            const bool meet = o.min.y - margin <= b.max.y + margin && b.min.y - margin <= o.max.y + margin &&
                              o.min.z - margin <= b.max.z + margin && b.min.z - margin <= o.max.z + margin;
            if (meet) ties[static_cast<std::size_t>(leaf)] = ties[static_cast<std::size_t>(other)] = 1;
        }
        open.push_back(leaf);
    }
    std::vector<int> out;
    for (int leaf : leaves)
        if (ties[static_cast<std::size_t>(leaf)]) out.push_back(leaf);
    std::sort(out.begin(), out.end());
    return out;
}

void PlainPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& drawn,
                    const std::vector<glm::vec2>& baseColors) {
    targets.ensurePlain();
    if (drawn.empty() || nearestDraws_ == 0) return;

    // Two surfaces tie when their depths along one ray lie within a quarter
    // of the tolerance; points on one ray that far apart in depth lie at
    // most that over the cosine of the ray's angle with the view direction
    // apart in space. Twice that, so that a turning camera rarely asks again.
    const double secant = view.orthographic ? 1.0
                                            : std::sqrt(1.0 + double(view.halfExtent.x) * view.halfExtent.x +
                                                        double(view.halfExtent.y) * view.halfExtent.y);
    const double needed = 0.25 * view.coincidence * secant;
    if (tieMargin_ < needed) {
        tieMargin_ = 2.0 * needed;
        std::vector<int> tying = mayTie(scene, leaves_, tieMargin_, kTieComparisons);
        std::reverse(tying.begin(), tying.end());  // the lowest leaf drawn last, and kept
        const std::vector<DrawElementsIndirectCommand> commands = scene.leafCommands(tying);
        gpu::Buffer::uploadGrowing(tieCommands_, "plain tie commands", commands);
        tieDraws_ = static_cast<GLsizei>(commands.size());
        tieCount_ = tying.size();
    }
    if (baseColors != uploadedColors_) {
        gpu::Buffer::uploadGrowing(colors_, "plain base colours", baseColors);
        uploadedColors_ = baseColors;
    }

    // Reversed depth (surface.vert, REVERSED_DEPTH): near / depth in
    // perspective, a float's relative precision at every depth. The tie
    // pass's pull: a quarter of the tolerance at the near plane, where a
    // depth step moves the window depth most, twice over.
    const double nearPlane = view.nearPlane, farPlane = view.farPlane;
    const double reach = 0.25 * view.coincidence;
    glm::vec3 depthTerms, pulled;
    if (view.orthographic) {
        const double span = farPlane - nearPlane;
        depthTerms = glm::vec3(static_cast<float>(farPlane / span), static_cast<float>(-1.0 / span), 0.0f);
        pulled = depthTerms + glm::vec3(0.0f, 0.0f, static_cast<float>(2.0 * reach / span));
    } else {
        depthTerms = glm::vec3(static_cast<float>(nearPlane), 0.0f, 0.0f);
        pulled = depthTerms + glm::vec3(0.0f, 0.0f, static_cast<float>(2.0 * reach / nearPlane));
    }
    setSurfaceView(nearest_, view);
    nearest_.setUniform(shader::kSurfaceReversedDepth, depthTerms);

    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(drawn.x, drawn.y, drawn.width, drawn.height);
    targets.plainTarget.bindForDraw();
    glClearNamedFramebufferfi(targets.plainTarget.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
    colors_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferPlainColors);
    scene.leafVertexArray().bind();

    // Nearest: every pixel written is marked for the shade pass.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, shader::kMarkWritten, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    nearest_.use();
    nearestCommands_.bind(GL_DRAW_INDIRECT_BUFFER);
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, nearestDraws_, 0);
    glDisable(GL_STENCIL_TEST);

    // Ties: the nearest depths copied aside; the leaves that can tie, last
    // the lowest, each fragment that may tie tested before its shader runs
    // (depth clamped: the pull may take a fragment past the near plane).
    if (tieDraws_ > 0) {
        if (nearestCopy_.width() != view.width || nearestCopy_.height() != view.height) {
            nearestCopy_ = gpu::Texture::create2D("plain nearest copy", GL_R32F, view.width, view.height);
        }
        glCopyImageSubData(targets.resultDepth.id(), GL_TEXTURE_2D, 0, drawn.x, drawn.y, 0, nearestCopy_.id(),
                           GL_TEXTURE_2D, 0, drawn.x, drawn.y, 0, drawn.width, drawn.height, 1);
        nearestCopy_.bindUnit(shader::kTexturePlainNearest);
        setSurfaceView(ties_, view);
        ties_.setUniform(shader::kSurfaceReversedDepth, pulled);
        ties_.setUniform(shader::kPlainTieTolerance, static_cast<float>(reach));
        ties_.use();
        glDepthFunc(GL_GEQUAL);
        glDepthMask(GL_FALSE);
        glEnable(GL_DEPTH_CLAMP);
        tieCommands_.bind(GL_DRAW_INDIRECT_BUFFER);
        glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, tieDraws_, 0);
        glDisable(GL_DEPTH_CLAMP);
        glDepthMask(GL_TRUE);
    }
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(GL_LESS);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    scene.vertexArray().bind();
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
