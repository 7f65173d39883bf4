#include "PlainPass.h"

#include <algorithm>
#include <cmath>

#include "ShadePass.h"
#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Box comparisons mayTie may spend before it takes every leaf as one that
// may tie: a few tens of milliseconds, once per scene and tolerance.
constexpr std::size_t kTieComparisons = std::size_t(1) << 25;

}  // namespace

PlainPass::PlainPass() = default;

gpu::Program& PlainPass::program(bool ties, const Output& output, const ViewSetup& view) {
    const std::optional<Lighting>& litAs = output.litAs;
    const std::size_t shading = !litAs ? 0 : *litAs == Lighting::Strata ? 1 : 2;
    std::optional<gpu::Program>& slot = programs_[output.shownOnly ? 1 : 0][ties ? 1 : 0][shading];
    if (!slot) {
        std::vector<gpu::ShaderDefine> defines{{"FACE_NORMAL", "1"}, {"GROUP_MEMBERS", ""}, {"REVERSED_DEPTH", ""}};
        if (output.shownOnly) defines.push_back({"SHOWN", ""});
        if (ties) defines.push_back({"TIE", ""});
        if (shading > 0) defines.push_back({"LIT", ""});
        if (shading == 2) defines.push_back({"OPENSCAD_LIGHT", ""});
        slot.emplace(gpu::Program::fromFiles(ties ? "plain ties" : "plain nearest",
                                             {"csg/surface.vert", "csg/plain.frag"}, defines));
    }
    gpu::Program& p = *slot;
    setSurfaceView(p, view);
    if (litAs) ShadePass::setLight(p, view, *litAs);
    return p;
}

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
    // The boxes, grown by the margin, in a grid of cells about as large as
    // the median box: a box is compared with those that share a cell with
    // it, so leaves apart cost no comparison (a grid of a million cubes is
    // a few million cell entries). A box over many cells (a base plate
    // under small parts) is compared with every box; a cell crowded past
    // kCrowded boxes counts them all as tying. Past `budget` comparisons
    // every leaf does.
    constexpr std::size_t kCrowded = 64, kMostCells = 64;
    auto box = [&](int leaf) -> const geometry::Bounds& { return scene.leaf(leaf).bounds; };
    auto meet = [&](int a, int b) {
        const geometry::Bounds &p = box(a), &q = box(b);
        for (int axis = 0; axis < 3; ++axis) {
            if (p.max[axis] + margin < q.min[axis] - margin || q.max[axis] + margin < p.min[axis] - margin)
                return false;
        }
        return true;
    };
    std::vector<int> present;
    present.reserve(leaves.size());
    for (int leaf : leaves)
        if (!box(leaf).empty()) present.push_back(leaf);
    std::vector<int> all(present);
    std::sort(all.begin(), all.end());
    if (present.size() < 2) return {};

    std::vector<double> extents;
    extents.reserve(present.size());
    for (int leaf : present) {
        const glm::dvec3 size = box(leaf).max - box(leaf).min;
        extents.push_back(std::max({size.x, size.y, size.z}));
    }
    std::nth_element(extents.begin(), extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2),
                     extents.end());
    geometry::Bounds whole;
    for (int leaf : present) whole.extend(box(leaf));
    const double cell = std::max({extents[extents.size() / 2] + 2.0 * margin, whole.diagonal() * 1e-6, 1e-300});

    // (cell key, leaf) for each cell a small box covers; the large ones apart.
    std::vector<std::pair<std::uint64_t, int>> entries;
    std::vector<int> large;
    auto cellOf = [&](double v, double origin) {
        return static_cast<std::int64_t>(std::floor((v - origin) / cell));
    };
    for (int leaf : present) {
        const geometry::Bounds& b = box(leaf);
        std::int64_t low[3], high[3];
        std::uint64_t count = 1;
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = cellOf(b.min[axis] - margin, whole.min[axis]);
            high[axis] = cellOf(b.max[axis] + margin, whole.min[axis]);
            count *= static_cast<std::uint64_t>(high[axis] - low[axis] + 1);
        }
        if (count > kMostCells) {
            large.push_back(leaf);
            continue;
        }
        for (std::int64_t x = low[0]; x <= high[0]; ++x)
            for (std::int64_t y = low[1]; y <= high[1]; ++y)
                for (std::int64_t z = low[2]; z <= high[2]; ++z) {
                    // 21 bits a coordinate, from one below the scene's corner.
                    const auto bits = [](std::int64_t c) { return static_cast<std::uint64_t>(c + 1) & 0x1fffff; };
                    entries.emplace_back(bits(x) << 42 | bits(y) << 21 | bits(z), leaf);
                }
    }
    if (large.size() * present.size() > budget) return all;
    std::vector<char> ties(scene.leaves().size(), 0);
    std::size_t comparisons = large.size() * present.size();
    for (int big : large) {
        for (int other : present) {
            if (other != big && meet(big, other)) ties[static_cast<std::size_t>(big)] = ties[static_cast<std::size_t>(other)] = 1;
        }
    }
    std::sort(entries.begin(), entries.end());
    for (std::size_t first = 0; first < entries.size();) {
        std::size_t last = first;
        while (last < entries.size() && entries[last].first == entries[first].first) ++last;
        const std::size_t n = last - first;
        if (n > kCrowded) {
            for (std::size_t i = first; i < last; ++i) ties[static_cast<std::size_t>(entries[i].second)] = 1;
        } else {
            comparisons += n * (n - 1) / 2;
            if (comparisons > budget) return all;
            for (std::size_t i = first; i < last; ++i)
                for (std::size_t j = i + 1; j < last; ++j) {
                    const int a = entries[i].second, b = entries[j].second;
                    if (meet(a, b)) ties[static_cast<std::size_t>(a)] = ties[static_cast<std::size_t>(b)] = 1;
                }
        }
        first = last;
    }
    std::vector<int> out;
    for (int leaf : all)
        if (ties[static_cast<std::size_t>(leaf)]) out.push_back(leaf);
    return out;
}

void PlainPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& drawn,
                    const std::vector<glm::vec2>& baseColors, const Output& output) {
    const bool shown = output.shownOnly;
    const std::optional<Lighting>& litAs = output.litAs;
    shown ? targets.ensureShown() : targets.ensurePlain();
    const gpu::Framebuffer& target = shown ? (litAs ? targets.plainShownLitTarget : targets.plainShownTarget)
                                           : (litAs ? targets.plainLitTarget : targets.plainTarget);
    if (shown) {
        // The clears in the framebuffer the draws use: llvmpipe then clears
        // each tile as it draws it, with no pass of its own.
        glDisable(GL_SCISSOR_TEST);
        if (litAs) {
            glClearNamedFramebufferfv(target.id(), GL_COLOR, 0, &output.background.r);
        } else {
            const PixelRect read = drawn.grown(1).intersection({0, 0, view.width, view.height});
            if (!read.empty()) {
                glEnable(GL_SCISSOR_TEST);
                glScissor(read.x, read.y, read.width, read.height);
                const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
                glClearNamedFramebufferfv(target.id(), GL_COLOR, 0, none);
                glDisable(GL_SCISSOR_TEST);
            }
        }
    }
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
    gpu::Program& nearest = program(false, output, view);
    nearest.setUniform(shader::kSurfaceReversedDepth, depthTerms);

    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(drawn.x, drawn.y, drawn.width, drawn.height);
    if (shown) {
        // The depths go to the tie pass alone.
        const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, tieDraws_ > 0 ? GL_COLOR_ATTACHMENT1 : GL_NONE};
        glNamedFramebufferDrawBuffers(target.id(), 2, buffers);
    }
    target.bindForDraw();
    // Lit and only shown, nothing reads marks: the depth has no stencil.
    const bool marked = !(shown && litAs);
    if (marked) {
        glClearNamedFramebufferfi(target.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
    } else {
        const float farthest = 0.0f;
        glClearNamedFramebufferfv(target.id(), GL_DEPTH, 0, &farthest);
    }
    colors_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferPlainColors);
    scene.leafVertexArray().bind();

    // Nearest: every pixel written is marked for the shade pass.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    if (marked) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, shader::kMarkWritten, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    }
    nearest.use();
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
        gpu::Program& ties = program(true, output, view);
        ties.setUniform(shader::kSurfaceReversedDepth, pulled);
        ties.setUniform(shader::kPlainTieTolerance, static_cast<float>(reach));
        ties.use();
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
