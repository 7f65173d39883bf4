#include "PlainPass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ShadePass.h"
#include "ShaderInterface.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Box comparisons mayTie and tyingTriangles may each spend before they give
// up (every leaf may tie; every triangle of those): a few tens of
// milliseconds, once per scene and tolerance.
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
    framesDrawn_ = 0;
    tieRefined_ = false;
    tieDraws_ = 0;
    tieCount_ = 0;
    tieTriangles_ = 0;
    uploadedColors_.clear();
}

namespace {

// Calls pair(i, j), i < j, for every two of `boxes` (none empty) that may
// meet once grown by `margin`, and for a few more, through a grid of cells
// about as large as the median box: boxes are compared with those that
// share a cell with them (a pair may come more than once), so boxes apart
// cost no comparison. A box over many cells (a base plate under small
// parts) is compared with every box. A cell crowded past `crowded` boxes
// calls crowd(i) for each of its boxes instead of comparing them. Returns
// false, having stopped, past `budget` comparisons.
template <class Pair, class Crowd>
bool nearPairs(std::span<const mesh::Bounds> boxes, double margin, std::size_t budget, std::size_t crowded,
               Pair&& pair, Crowd&& crowd) {
    constexpr std::size_t kMostCells = 64;
    if (boxes.size() < 2) return true;
    std::vector<double> extents;
    extents.reserve(boxes.size());
    mesh::Bounds whole;
    for (const mesh::Bounds& b : boxes) {
        const glm::dvec3 size = b.max - b.min;
        extents.push_back(std::max({size.x, size.y, size.z}));
        whole.extend(b);
    }
    std::nth_element(extents.begin(), extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2),
                     extents.end());
    const double cell = std::max({extents[extents.size() / 2] + 2.0 * margin, whole.diagonal() * 1e-6, 1e-300});

    // (cell key, box) for each cell a small box covers; the large ones apart.
    std::vector<std::pair<std::uint64_t, std::size_t>> entries;
    std::vector<std::size_t> large;
    auto cellOf = [&](double v, double origin) {
        return static_cast<std::int64_t>(std::floor((v - origin) / cell));
    };
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const mesh::Bounds& b = boxes[i];
        std::int64_t low[3], high[3];
        std::uint64_t count = 1;
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = cellOf(b.min[axis] - margin, whole.min[axis]);
            high[axis] = cellOf(b.max[axis] + margin, whole.min[axis]);
            count *= static_cast<std::uint64_t>(high[axis] - low[axis] + 1);
        }
        if (count > kMostCells) {
            large.push_back(i);
            continue;
        }
        for (std::int64_t x = low[0]; x <= high[0]; ++x)
            for (std::int64_t y = low[1]; y <= high[1]; ++y)
                for (std::int64_t z = low[2]; z <= high[2]; ++z) {
                    // 21 bits a coordinate, from one below the scene's corner.
                    const auto bits = [](std::int64_t c) { return static_cast<std::uint64_t>(c + 1) & 0x1fffff; };
                    entries.emplace_back(bits(x) << 42 | bits(y) << 21 | bits(z), i);
                }
    }
    std::size_t comparisons = large.size() * boxes.size();
    if (comparisons > budget) return false;
    for (std::size_t big : large) {
        for (std::size_t other = 0; other < boxes.size(); ++other) {
            if (other != big) pair(std::min(big, other), std::max(big, other));
        }
    }
    std::sort(entries.begin(), entries.end());
    for (std::size_t first = 0; first < entries.size();) {
        std::size_t last = first;
        while (last < entries.size() && entries[last].first == entries[first].first) ++last;
        const std::size_t n = last - first;
        if (n > crowded) {
            for (std::size_t i = first; i < last; ++i) crowd(entries[i].second);
        } else {
            comparisons += n * (n - 1) / 2;
            if (comparisons > budget) return false;
            for (std::size_t i = first; i < last; ++i)
                for (std::size_t j = i + 1; j < last; ++j) {
                    const std::size_t a = entries[i].second, b = entries[j].second;
                    pair(std::min(a, b), std::max(a, b));
                }
        }
        first = last;
    }
    return true;
}

bool boxesMeet(const mesh::Bounds& p, const mesh::Bounds& q, double margin) {
    for (int axis = 0; axis < 3; ++axis) {
        if (p.max[axis] + margin < q.min[axis] - margin || q.max[axis] + margin < p.min[axis] - margin) return false;
    }
    return true;
}

}  // namespace

std::vector<int> PlainPass::mayTie(const SceneBuffers& scene, std::span<const int> leaves, double margin,
                                   std::size_t budget) {
    // A cell crowded past kCrowded boxes counts them all as tying; past
    // `budget` comparisons every leaf does.
    constexpr std::size_t kCrowded = 64;
    std::vector<int> present;
    std::vector<mesh::Bounds> boxes;
    present.reserve(leaves.size());
    for (int leaf : leaves) {
        if (scene.leaf(leaf).bounds.empty()) continue;
        present.push_back(leaf);
        boxes.push_back(scene.leaf(leaf).bounds);
    }
    if (present.size() < 2) return {};
    std::vector<char> ties(present.size(), 0);
    const bool whole = nearPairs(
        boxes, margin, budget, kCrowded,
        [&](std::size_t a, std::size_t b) {
            if (boxesMeet(boxes[a], boxes[b], margin)) ties[a] = ties[b] = 1;
        },
        [&](std::size_t a) { ties[a] = 1; });
    std::vector<int> out;
    for (std::size_t i = 0; i < present.size(); ++i)
        if (!whole || ties[i]) out.push_back(present[i]);
    std::sort(out.begin(), out.end());
    return out;
}

std::optional<PlainPass::TieDraws> PlainPass::tyingTriangles(const SceneBuffers& scene, std::span<const int> leaves,
                                                             double margin, std::size_t budget) {
    // A cell of more triangles than this counts them all as tying: the
    // tip of a cone, the pole of a sphere.
    constexpr std::size_t kCrowded = 256;
    std::size_t total = 0;
    for (int leaf : leaves) total += scene.leaf(leaf).indexCount / 3;
    if (total > kMostTieTriangles) return std::nullopt;

    // Every triangle of the leaves, as drawn, with its leaf's place in `leaves`.
    struct Triangle {
        glm::vec3 corner[3];
        glm::vec3 normal;  // unit, or 0 for a triangle with no area
        std::uint32_t leaf;
    };
    std::vector<Triangle> triangles;
    std::vector<mesh::Bounds> boxes;
    std::vector<SceneBuffers::LeafTriangles> drawn(leaves.size());
    std::vector<std::size_t> firstTriangle(leaves.size() + 1, 0);
    triangles.reserve(total);
    boxes.reserve(total);
    for (std::size_t l = 0; l < leaves.size(); ++l) {
        drawn[l] = scene.leafTriangles(leaves[l]);
        firstTriangle[l] = triangles.size();
        const std::vector<glm::vec3>& corners = drawn[l].corners;
        for (std::size_t c = 0; c + 2 < corners.size(); c += 3) {
            Triangle t{{corners[c], corners[c + 1], corners[c + 2]}, {}, static_cast<std::uint32_t>(l)};
            const glm::dvec3 a(t.corner[0]);
            const glm::dvec3 n = glm::cross(glm::dvec3(t.corner[1]) - a, glm::dvec3(t.corner[2]) - a);
            const double length = glm::length(n);
            t.normal = length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f);
            mesh::Bounds box;
            for (const glm::vec3& p : t.corner) box.extend(glm::dvec3(p));
            triangles.push_back(t);
            boxes.push_back(box);
        }
    }
    firstTriangle[leaves.size()] = triangles.size();

    // Two triangles of different leaves hold points `margin` apart at most
    // only if each has a corner within the margin of the other's plane on
    // either side, or touches it (its corners' heights over it bracket
    // that point's): the test keeps every such pair and a few more. (The
    // unit normal in floats errs by far less than the margin's last
    // quarter, PlainPass::run.)
    auto reaches = [&](const Triangle& t, const Triangle& u) {
        if (t.normal == glm::vec3(0.0f)) return true;
        const glm::dvec3 n(t.normal), origin(t.corner[0]);
        double low = INFINITY, high = -INFINITY;
        for (const glm::vec3& p : u.corner) {
            const double h = glm::dot(n, glm::dvec3(p) - origin);
            low = std::min(low, h);
            high = std::max(high, h);
        }
        return low <= margin && high >= -margin;
    };
    std::vector<char> ties(triangles.size(), 0);
    const bool whole = nearPairs(
        boxes, margin, budget, kCrowded,
        [&](std::size_t a, std::size_t b) {
            const Triangle &t = triangles[a], &u = triangles[b];
            if (t.leaf == u.leaf || !boxesMeet(boxes[a], boxes[b], margin)) return;
            if (reaches(t, u) && reaches(u, t)) ties[a] = ties[b] = 1;
        },
        [&](std::size_t a) { ties[a] = 1; });
    if (!whole) return std::nullopt;

    // The draws: the lowest leaf last, each leaf's tying triangles.
    TieDraws out;
    for (std::size_t l = leaves.size(); l-- > 0;) {
        const std::size_t first = out.indices.size();
        for (std::size_t k = firstTriangle[l]; k < firstTriangle[l + 1]; ++k) {
            if (!ties[k]) continue;
            const std::size_t c = 3 * (k - firstTriangle[l]);
            out.indices.insert(out.indices.end(), drawn[l].indices.begin() + static_cast<std::ptrdiff_t>(c),
                               drawn[l].indices.begin() + static_cast<std::ptrdiff_t>(c + 3));
        }
        if (out.indices.size() == first) continue;
        out.commands.push_back({static_cast<GLuint>(out.indices.size() - first), 1, static_cast<GLuint>(first), 0,
                                static_cast<GLuint>(leaves[l])});
        out.triangles += (out.indices.size() - first) / 3;
    }
    return out;
}

void PlainPass::findTies(const SceneBuffers& scene, const ViewSetup& view) {
    // Two surfaces tie when their depths along one ray lie within a quarter
    // of the tolerance; points on one ray that far apart in depth lie at
    // most that over the cosine of the ray's angle with the view direction
    // apart in space. Twice that, so that a turning camera rarely asks
    // again, and asked again while a quarter of the margin is left for
    // the rounding of the shader's depths.
    const double secant = view.orthographic ? 1.0
                                            : std::sqrt(1.0 + double(view.halfExtent.x) * view.halfExtent.x +
                                                        double(view.halfExtent.y) * view.halfExtent.y);
    const double needed = 0.25 * view.coincidence * secant;
    // The first frame of a scene draws the tying leaves whole: sorting out
    // their triangles costs more CPU time than that second draw of them
    // (about 0.2 s for 300,000 triangles), and a single image (strata-render)
    // never gains it back. The next frame sorts them out.
    const bool refine = framesDrawn_ > 0 && tieAllOf_ && !tieRefined_;
    if (nearestDraws_ > 0 && (tieMargin_ < 1.25 * needed || refine)) {
        if (tieMargin_ < 1.25 * needed) tieMargin_ = 2.0 * needed;
        // The leaves whose boxes meet, then of those the triangles that
        // come near another leaf's; where those are too many to sort out,
        // every triangle of the leaves.
        std::vector<int> tying = mayTie(scene, leaves_, tieMargin_, kTieComparisons);
        std::optional<TieDraws> draws;
        if (framesDrawn_ > 0) {
            draws = tyingTriangles(scene, tying, tieMargin_, kTieComparisons);
            tieRefined_ = true;
        }
        if (!draws) {
            std::reverse(tying.begin(), tying.end());  // the lowest leaf drawn last, and kept
            draws.emplace();
            draws->commands = scene.leafCommands(tying);
            draws->allOf = true;
        }
        gpu::Buffer::uploadGrowing(tieCommands_, "plain tie commands", draws->commands);
        tieDraws_ = static_cast<GLsizei>(draws->commands.size());
        tieCount_ = draws->commands.size();
        tieTriangles_ = draws->triangles;
        if (!draws->allOf) {
            gpu::Buffer::uploadGrowing(tieIndices_, "plain tie triangles", draws->indices);
            tieVertexArray_ = scene.leafVertexArrayOver(tieIndices_);
        }
        tieAllOf_ = draws->allOf;
    }
}

void PlainPass::prepareShown(const gpu::Framebuffer& target, const ViewSetup& view, const PixelRect& drawn,
                             const Output& output) {
    // Only what is read after: the depths where the tie pass runs or
    // the blending passes read them, the leaf codes for those passes.
    const bool ties = tieDraws_ > 0 && !drawn.empty();
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0,
                               ties || output.keepResult ? GLenum(GL_COLOR_ATTACHMENT1) : GLenum(GL_NONE),
                               output.keepResult ? GLenum(GL_COLOR_ATTACHMENT2) : GLenum(GL_NONE)};
    glNamedFramebufferDrawBuffers(target.id(), 3, buffers);
    // The clears in the framebuffer the draws use: llvmpipe then clears
    // each tile as it draws it, with no pass of its own.
    glDisable(GL_SCISSOR_TEST);
    if (output.litAs) {
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
    if (output.keepResult) {
        // Beside the CSG, the evaluator reads them inside `drawn` only (a
        // read-back cleared the whole frame before).
        const PixelRect read = drawn.intersection({0, 0, view.width, view.height});
        if (output.beside) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(read.x, read.y, read.width, read.height);
        }
        const float miss[4] = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
        const GLint noLeaf[4] = {shader::kLeafMiss, 0, 0, 0};
        glClearNamedFramebufferfv(target.id(), GL_COLOR, 1, miss);
        glClearNamedFramebufferiv(target.id(), GL_COLOR, 2, noLeaf);
        glDisable(GL_SCISSOR_TEST);
    }
}

// The depth to 0, the farthest reversed depth, and the marks to none.
void PlainPass::clearDepth(const gpu::Framebuffer& target, bool marked) {
    if (marked) {
        glClearNamedFramebufferfi(target.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
    } else {
        const float farthest = 0.0f;
        glClearNamedFramebufferfv(target.id(), GL_DEPTH, 0, &farthest);
    }
}

// Reversed depth (surface.vert, REVERSED_DEPTH): near / depth in
// perspective, a float's relative precision at every depth. The tie
// shader compares the fragments' plane depths (surface-depth.glsl),
// which one plane gives alike to every leaf, within a quarter of the
// tolerance. The depth test before it compares interpolated window
// depths, which part one plane's copies by up to 2^-20 of the scene's
// scale (as measured before plane depths), so the pull that lets every
// copy through reaches 16 times that far, at the near plane, where a
// depth step moves the window depth most, twice over.
PlainPass::ReversedDepth PlainPass::reversedDepth(const ViewSetup& view) {
    const double nearPlane = view.nearPlane, farPlane = view.farPlane;
    ReversedDepth depth;
    depth.reach = 0.25 * view.coincidence;
    const double pull = 16.0 * depth.reach;
    if (view.orthographic) {
        const double span = farPlane - nearPlane;
        depth.terms = glm::vec3(static_cast<float>(farPlane / span), static_cast<float>(-1.0 / span), 0.0f);
        depth.pulled = depth.terms + glm::vec3(0.0f, 0.0f, static_cast<float>(2.0 * pull / span));
    } else {
        depth.terms = glm::vec3(static_cast<float>(nearPlane), 0.0f, 0.0f);
        depth.pulled = depth.terms + glm::vec3(0.0f, 0.0f, static_cast<float>(2.0 * pull / nearPlane));
    }
    return depth;
}

// Ties: the nearest depths copied aside; the leaves that can tie, last
// the lowest, each fragment that may tie tested before its shader runs
// (depth clamped: the pull may take a fragment past the near plane).
void PlainPass::drawTies(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
                         const PixelRect& drawn, const Output& output, const ReversedDepth& depth) {
    if (nearestCopy_.width() != view.width || nearestCopy_.height() != view.height) {
        nearestCopy_ = gpu::Texture::create2D("plain nearest copy", GL_R32F, view.width, view.height);
    }
    glCopyImageSubData(targets.resultDepth.id(), GL_TEXTURE_2D, 0, drawn.x, drawn.y, 0, nearestCopy_.id(),
                       GL_TEXTURE_2D, 0, drawn.x, drawn.y, 0, drawn.width, drawn.height, 1);
    nearestCopy_.bindUnit(shader::kTexturePlainNearest);
    gpu::Program& ties = program(true, output, view);
    ties.setUniform(shader::kSurfaceReversedDepth, depth.pulled);
    ties.setUniform(shader::kPlainTieTolerance, static_cast<float>(depth.reach));
    ties.use();
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    (tieAllOf_ ? scene.leafVertexArray() : tieVertexArray_).bind();
    tieCommands_.bind(GL_DRAW_INDIRECT_BUFFER);
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, tieDraws_, 0);
    glDisable(GL_DEPTH_CLAMP);
    glDepthMask(GL_TRUE);
}

void PlainPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& drawn,
                    const std::vector<glm::vec2>& baseColors, const Output& output) {
    const bool shown = output.shownOnly;
    const std::optional<Lighting>& litAs = output.litAs;
    shown ? targets.ensureShown() : targets.ensurePlain();
    const gpu::Framebuffer& target = shown ? (litAs ? targets.plainShownLitTarget : targets.plainShownTarget)
                                           : (litAs ? targets.plainLitTarget : targets.plainTarget);
    findTies(scene, view);
    if (shown) {
        prepareShown(target, view, drawn, output);
    } else if (litAs) {
        glClearNamedFramebufferfv(targets.colorTarget.id(), GL_COLOR, 0, &output.background.r);
    }
    // Lit and only shown, nothing reads marks: the depth has no stencil.
    const bool marked = !(shown && litAs);
    // Read after beyond the leaves' pixels: cleared over the whole frame,
    // whether anything is drawn or not.
    if (output.depthRead) {
        glDisable(GL_SCISSOR_TEST);
        clearDepth(target, marked);
    }
    if (drawn.empty() || nearestDraws_ == 0) return;
    ++framesDrawn_;

    if (baseColors != uploadedColors_) {
        gpu::Buffer::uploadGrowing(colors_, "plain base colours", baseColors);
        uploadedColors_ = baseColors;
    }

    const ReversedDepth depth = reversedDepth(view);
    gpu::Program& nearest = program(false, output, view);
    nearest.setUniform(shader::kSurfaceReversedDepth, depth.terms);

    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(drawn.x, drawn.y, drawn.width, drawn.height);
    target.bindForDraw();
    if (!output.depthRead) clearDepth(target, marked);
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
        glStencilFunc(GL_ALWAYS, output.beside ? shader::kMarkPlain : shader::kMarkWritten, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    }
    nearest.use();
    nearestCommands_.bind(GL_DRAW_INDIRECT_BUFFER);
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, nearestDraws_, 0);
    glDisable(GL_STENCIL_TEST);

    if (tieDraws_ > 0) drawTies(targets, scene, view, drawn, output, depth);
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
