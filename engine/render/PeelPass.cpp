#include "PeelPass.h"

#include <algorithm>
#include <cfloat>
#include <limits>
#include <string>

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

bool canBatch() {
    return epoxy_has_gl_extension("GL_ARB_shader_draw_parameters") &&
           epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array");
}

}  // namespace

PeelPass::PeelPass()
    : first_(gpu::Program::fromFiles("peel first", {"csg/surface.vert", "csg/peel.frag"}, {{"PEEL_FIRST", ""}})),
      next_(gpu::Program::fromFiles("peel next", {"csg/surface.vert", "csg/peel.frag"})),
      batched_(canBatch()),
      target_("peel"),
      counted_("peel counted"),
      deeper_(gpu::Program::fromFiles("peel deeper", {"common/fullscreen.vert", "csg/deeper.frag"})),
      drawn_("peel drawn", GL_ANY_SAMPLES_PASSED),
      deeperDrawn_("peel deeper drawn", GL_ANY_SAMPLES_PASSED),
      collect_(gpu::Program::fromFiles("peel collect", {"csg/surface.vert", "csg/peel.frag"},
                                       {{"PEEL_FIRST", ""}, {"COLLECT", ""}})),
      resolve_(gpu::Program::fromFiles("peel resolve", {"common/fullscreen.vert", "csg/resolve.frag"})),
      listTarget_("peel lists"),
      resolveStats_("peel resolve stats", 2 * sizeof(GLuint)) {
    if (batched_) {
        batch_ = gpu::Program::fromFiles("peel batch", {"csg/surface.vert", "csg/peel.frag"},
                                         {{"PEEL_FIRST", ""}, {"LAYERED", ""}});
    }
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxArrayLayers_);
    target_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    counted_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
}

namespace {

// Whether operand k is a group (of convex operands, or a union).
bool isGroup(const PeelRequest& request, std::size_t k) {
    return k < request.groups.size() && request.groups[k].size() > 1;
}

// Whether operand k takes one pass (one layer): convex, a group, or first layer only.
bool onePass(const LeafRange& leaf, const PeelRequest& request, std::size_t k) {
    return leaf.convex || isGroup(request, k) || (k < request.firstLayerOnly.size() && request.firstLayerOnly[k]);
}

// Whether operand k is first tried through fragment lists.
bool listed(const LeafRange& leaf, const PeelRequest& request, std::size_t k) {
    return !onePass(leaf, request, k) && request.listTriangles >= 0 &&
           leaf.indexCount / 3 >= static_cast<std::size_t>(request.listTriangles);
}

// Whether some operand with triangles in the tile is first tried through
// fragment lists: then the lists' images are needed (and counted).
bool anyListed(const SceneBuffers& scene, std::span<const int> operandLeaves, std::span<const char> inTile,
               const PeelRequest& request) {
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        if (!inTile[k]) continue;
        const LeafRange& leaf = scene.leaf(operandLeaves[k]);
        if (leaf.indexCount > 0 && listed(leaf, request, k)) return true;
    }
    return false;
}

}  // namespace

PeelPass::LayerEstimate PeelPass::estimateLayers(const SceneBuffers& scene, std::span<const int> operandLeaves,
                                                 std::span<const char> inTile, const PeelRequest& request) {
    const int fixedLayers = request.fixedLayers;
    LayerEstimate estimate;
    estimate.layers = fixedLayers > 0 ? 0 : 1;  // auto: one scratch layer for the empty check
    int groups = 0;
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        if (!inTile[k]) continue;
        groups += isGroup(request, k) ? 1 : 0;
        const LeafRange& leaf = scene.leaf(operandLeaves[k]);
        if (leaf.indexCount == 0) continue;
        estimate.layers += onePass(leaf, request, k) ? 1 : (fixedLayers > 0 ? fixedLayers : 2);
    }
    // Groups: their scratch images and ids.
    if (groups > 0) estimate.scratchBytesPerPixel += GroupPeel::bytesPerPixel(groups);
    // Collecting: the lists' images, and auto's room for a list's every
    // layer while it is resolved (the guess above gives each operand 2).
    if (anyListed(scene, operandLeaves, inTile, request)) {
        estimate.scratchBytesPerPixel += kCollectScratchBytes;
        estimate.layers += fixedLayers > 0 ? 0 : kCollectCapacity / 2 - 2;
    }
    estimate.layers = std::max(estimate.layers, 1);
    return estimate;
}

bool PeelPass::reserve(int width, int height, int needed, int keep, std::size_t budgetBytes) {
    if (!counts_.id() || counts_.width() < width || counts_.height() < height) {
        counts_ = gpu::Texture::create2D("peel counts", GL_STENCIL_INDEX8, width, height);
        counted_.attachTexture(GL_STENCIL_ATTACHMENT, counts_);
    }
    if (layers_.id() && layers_.width() >= width && layers_.height() >= height && layers_.layers() >= needed &&
        layers_.byteSize() <= budgetBytes) {
        return true;
    }
    const std::size_t perLayer = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * kBytesPerTexel;
    const std::size_t byBudget = budgetBytes / perLayer;
    const int most = static_cast<int>(std::min<std::size_t>(byBudget, static_cast<std::size_t>(maxArrayLayers_)));
    if (needed > most) return false;
    // Grow geometrically so an auto-peeled scene reallocates a few times at most.
    const int grown = layers_.id() ? std::max(needed, layers_.layers() * 3 / 2) : needed;
    const int capacity = std::min(grown, most);
    gpu::Texture bigger = gpu::Texture::create2DArray("peel layers", GL_RG32F, width, height, capacity);
    if (keep > 0 && layers_.id()) {
        glCopyImageSubData(layers_.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, bigger.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0,
                           0, std::min(width, layers_.width()), std::min(height, layers_.height()), keep);
    }
    layers_ = std::move(bigger);
    ++allocations_;
    return true;
}

PixelRect PeelPass::region(const PixelRect& rect, const PixelRect& tile, int block) {
    const int x0 = std::max(0, (rect.x - tile.x) / block * block);
    const int y0 = std::max(0, (rect.y - tile.y) / block * block);
    const int x1 = std::min(tile.width, (rect.x + rect.width - tile.x + block - 1) / block * block);
    const int y1 = std::min(tile.height, (rect.y + rect.height - tile.y + block - 1) / block * block);
    return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

void PeelPass::clearLayers(const PixelRect& valid, int first, int count) {
    const float cleared[2] = {-FLT_MAX, -FLT_MAX};
    glClearTexSubImage(layers_.id(), 0, valid.x, valid.y, first, valid.width, valid.height, count, GL_RG, GL_FLOAT,
                       cleared);
}

bool PeelPass::run(const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
                   std::span<const int> operandLeaves, std::span<const PixelRect> rects, int block,
                   const PeelRequest& request, std::vector<OperandLayers>& out) {
    out.assign(operandLeaves.size(), {});
    passes_ = 0;
    allocations_ = 0;
    collected_ = 0;
    std::vector<char> inTile(operandLeaves.size());
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) inTile[k] = rects[k].intersects(tile) ? 1 : 0;
    // The lists' images stay from frame to frame only while some operand may
    // be collected: otherwise their memory is outside the budget's count.
    if (fragmentCounts_.id() && !anyListed(scene, operandLeaves, inTile, request)) {
        fragments_ = {};
        fragmentCounts_ = {};
    }
    // The layer texture holds the layers alone: the groups' and lists' images
    // are textures of their own, out of the same budget.
    const LayerEstimate estimate = estimateLayers(scene, operandLeaves, inTile, request);
    const std::size_t scratch = estimate.scratchBytesPerPixel * static_cast<std::size_t>(tile.width) *
                                static_cast<std::size_t>(tile.height);
    const std::size_t layerBudget = request.budgetBytes > scratch ? request.budgetBytes - scratch : 0;
    if (!reserve(tile.width, tile.height, estimate.layers, 0, layerBudget)) return false;

    const Job job{scene, tile, operandLeaves, rects, block, request, inTile, layerBudget};
    beginPasses(scene, view, tile);
    // Groups first, then the convex batch, one layer each (reserve() made
    // room for all); then the other operands one by one.
    int used = peelGroups(job, view, out);
    if (batched_) used = peelConvexBatch(job, out, used);
    bool fits = true;
    for (std::size_t k = 0; k < operandLeaves.size(); ++k) {
        if (!inTile[k] || scene.leaf(operandLeaves[k]).indexCount == 0 || out[k].count > 0) continue;
        const int count = peelOperand(job, k, used);
        if (count == kOverBudget) {
            fits = false;
            break;
        }
        out[k] = {used, count};
        used += count;
    }
    endPasses();
    return fits;
}

void PeelPass::beginPasses(const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile) {
    setSurfaceView(first_, view, {tile.x, tile.y});
    setSurfaceView(next_, view, {tile.x, tile.y});
    setSurfaceView(collect_, view, {tile.x, tile.y});
    if (batched_) setSurfaceView(batch_, view, {tile.x, tile.y});
    glViewport(-tile.x, -tile.y, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MAX);
    glBlendFunc(GL_ONE, GL_ONE);
    scene.vertexArray().bind();
}

void PeelPass::endPasses() {
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    target_.detach(GL_COLOR_ATTACHMENT0);
    counted_.detach(GL_COLOR_ATTACHMENT0);
    gpu::checkErrors();
}

int PeelPass::peelGroups(const Job& job, const ViewSetup& view, std::vector<OperandLayers>& out) {
    int groups = 0;
    for (std::size_t k = 0; k < job.operandLeaves.size(); ++k)
        groups += job.inTile[k] && isGroup(job.request, k) ? 1 : 0;
    if (groups == 0) {
        group_.release();
        return 0;
    }
    glDisable(GL_BLEND);
    group_.begin(view, job.tile, groups);
    int used = 0;
    for (std::size_t k = 0; k < job.operandLeaves.size(); ++k) {
        if (!job.inTile[k] || !isGroup(job.request, k)) continue;
        const PixelRect valid = job.valid(k);
        clearLayers(valid, used, 1);
        // The groups take the first layers, so a group's layer is also its
        // index among the tile's groups: its layer of the ids.
        out[k] = {used, 1, used};
        const bool unite = k < job.request.unionGroups.size() && job.request.unionGroups[k];
        const bool ties = GroupPeel::tiesWanted(job.scene, job.request.groups[k], unite);
        group_.peel(job.scene, job.request.groups[k], valid, layers_, used, used, ties, unite);
        ++used;
        passes_ += ties ? 4 : 2;  // entries, exits, and their ties (GroupPeel.h)
    }
    glEnable(GL_BLEND);
    return used;
}

int PeelPass::peelConvexBatch(const Job& job, std::vector<OperandLayers>& out, int used) {
    std::vector<DrawElementsIndirectCommand> commands;
    std::vector<std::uint32_t> drawLayers;
    for (std::size_t k = 0; k < job.operandLeaves.size(); ++k) {
        const LeafRange& range = job.scene.leaf(job.operandLeaves[k]);
        if (!job.inTile[k] || range.indexCount == 0 || out[k].count > 0 || !onePass(range, job.request, k)) continue;
        out[k] = {used++, 1};
        // The layer is cleared where the evaluator reads it; the operand's
        // fragments fall inside its rectangle, so nothing else is touched.
        clearLayers(job.valid(k), out[k].first, 1);
        commands.push_back({static_cast<GLuint>(range.indexCount), 1, static_cast<GLuint>(range.firstIndex), 0, 0});
        drawLayers.push_back(static_cast<std::uint32_t>(out[k].first));
    }
    if (commands.empty()) return used;
    gpu::Buffer::uploadGrowing(commands_, "peel batch commands", commands);
    gpu::Buffer::uploadGrowing(drawLayers_, "peel batch layers", drawLayers);
    target_.attachTexture(GL_COLOR_ATTACHMENT0, layers_);  // layered: gl_Layer picks the layer
    target_.bindForDraw();
    glScissor(0, 0, job.tile.width, job.tile.height);
    drawLayers_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferDrawLayers);
    commands_.bind(GL_DRAW_INDIRECT_BUFFER);
    batch_.use();
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(commands.size()), 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    passes_ += static_cast<int>(commands.size());
    return used;
}

int PeelPass::peelOperand(const Job& job, std::size_t k, int first) {
    const int leaf = job.operandLeaves[k];
    const LeafRange& range = job.scene.leaf(leaf);
    const PixelRect valid = job.valid(k);
    glScissor(valid.x, valid.y, valid.width, valid.height);
    // Convex: one pass holds every surface (first layer only: all that
    // matters).
    if (onePass(range, job.request, k)) return peelFixed(job, leaf, first, 1);
    if (listed(range, job.request, k)) {
        // One pass through fragment lists where they hold every fragment;
        // else pass by pass.
        const int count = peelThroughLists(job, leaf, valid, first);
        if (count != kListsOverflowed) return count;
    }
    return job.request.fixedLayers > 0 ? peelFixed(job, leaf, first, job.request.fixedLayers)
                                       : peelAuto(job, leaf, first);
}

int PeelPass::peelFixed(const Job& job, int leaf, int first, int passes) {
    for (int pass = 0; pass < passes; ++pass) {
        const int layer = first + pass;
        if (!reserve(job.tile.width, job.tile.height, layer + 1, layer, job.layerBudget)) return kOverBudget;
        peelPass(job.scene, leaf, layer, pass, false);
    }
    return passes;
}

int PeelPass::peelAuto(const Job& job, int leaf, int first) {
    for (int pass = 0;; ++pass) {
        if (pass > 0) {
            // Surfaces left somewhere? Waiting for that answer also finishes
            // the last pass, so its own query costs no wait.
            const bool deeper = anyDeeperThan(2 * pass);
            // Surfaces at one depth peel together, so the counts can promise
            // more than was left: then the last layer is scratch.
            if (drawn_.result() == 0) return pass - 1;
            if (!deeper) return pass;
        }
        const int layer = first + pass;
        if (!reserve(job.tile.width, job.tile.height, layer + 1, layer, job.layerBudget)) return kOverBudget;
        peelPass(job.scene, leaf, layer, pass, true);
    }
}

void PeelPass::peelPass(const SceneBuffers& scene, int leaf, int layer, int pass, bool automatic) {
    const float cleared[4] = {-FLT_MAX, -FLT_MAX, 0.0f, 0.0f};
    counted_.attachLayer(GL_COLOR_ATTACHMENT0, layers_, layer);
    counted_.bindForDraw();
    counted_.clearColor(0, cleared);
    if (automatic) {
        // The first pass counts each pixel's surfaces; the later ones skip
        // the pixels whose surfaces are all peeled.
        glEnable(GL_STENCIL_TEST);
        if (pass == 0) {
            const GLint zero = 0;
            glClearNamedFramebufferiv(counted_.id(), GL_STENCIL, 0, &zero);
            glStencilFunc(GL_ALWAYS, 0, 0xff);
            glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
        } else {
            glStencilFunc(GL_LESS, 2 * pass, 0xff);
            glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        }
    }
    gpu::Program& program = pass == 0 ? first_ : next_;
    if (pass > 0) {
        // The previous layer was rendered by the last draw: make it
        // readable (ARB_texture_barrier, core in 4.5).
        glTextureBarrier();
        layers_.bindUnit(shader::kTextureLayers);
        program.setUniform(shader::kPeelPreviousLayer, layer - 1);
    }
    program.use();
    if (automatic) drawn_.begin();
    scene.drawLeaf(leaf);
    ++passes_;
    if (automatic) {
        drawn_.end();
        glDisable(GL_STENCIL_TEST);
    }
}

bool PeelPass::anyDeeperThan(int surfaces) {
    if (surfaces >= 255) return true;
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_LESS, surfaces, 0xff);  // passes where surfaces < count
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    deeper_.use();
    // The scene's vertex array stays bound: the fullscreen triangle reads no
    // attribute, and on llvmpipe each switch of vertex array between the
    // operand's draws cost more than the draw itself.
    deeperDrawn_.begin();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    deeperDrawn_.end();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    return deeperDrawn_.result() != 0;
}

int PeelPass::peelThroughLists(const Job& job, int leaf, const PixelRect& valid, int first) {
    const PixelRect& tile = job.tile;
    const bool automatic = job.request.fixedLayers <= 0;
    const int layerCount = automatic ? kCollectCapacity / 2 : job.request.fixedLayers;
    // The lists' images come out of the budget (job.layerBudget is without them).
    if (!reserve(tile.width, tile.height, first + layerCount, first, job.layerBudget)) return kOverBudget;
    // The lists' images are the tile's size exactly: the budget counts them so
    // (run's reserve), and a larger pair left from an earlier frame would
    // hold memory the budget does not know of.
    if (!fragmentCounts_.id() || fragmentCounts_.width() != tile.width || fragmentCounts_.height() != tile.height) {
        fragments_ =
            gpu::Texture::create2DArray("peel fragment lists", GL_R32F, tile.width, tile.height, kCollectCapacity);
        fragmentCounts_ = gpu::Texture::create2D("peel fragment counts", GL_R32UI, tile.width, tile.height);
        const GLuint none = 0;  // from then on the resolve sets each count it read back to 0
        fragmentCounts_.clear(GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
        glNamedFramebufferParameteri(listTarget_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, tile.width);
        glNamedFramebufferParameteri(listTarget_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, tile.height);
        ++allocations_;
    }
    // The resolve writes only the layers a pixel has; the rest read as cleared.
    clearLayers(valid, first, layerCount);
    resolveStats_.clearToZero();

    listTarget_.bindForDraw();
    fragmentCounts_.bindImage(shader::kImageFragmentCounts, GL_READ_WRITE);
    fragments_.bindImage(shader::kImageFragments, GL_READ_WRITE);
    collect_.use();
    job.scene.drawLeaf(leaf);
    ++passes_;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    layers_.bindImage(shader::kImageLayers, GL_WRITE_ONLY);
    resolveStats_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferResolveStats);
    resolve_.use();
    resolve_.setUniform(shader::kResolveFirstLayer, first);
    resolve_.setUniform(shader::kResolveLayerCount, std::min(layerCount, kCollectCapacity / 2));
    glDrawArrays(GL_TRIANGLES, 0, 3);  // the scene's vertex array stays bound, see anyDeeperThan
    // Image stores become visible to later image loads and sampling (the
    // evaluator), copies and read-backs of the layers (reserve(), the debug
    // views), and the stats' read-back.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint most[2] = {0, 0};  // layers, and fragments where a list overflowed
    resolveStats_.downloadSpan(std::span<GLuint>(most));
    if (most[1] > 0) return kListsOverflowed;
    ++collected_;
    return automatic ? static_cast<int>(most[0]) : layerCount;
}

}  // namespace strata::render
