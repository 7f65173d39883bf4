#include "NormalPass.h"

#include <algorithm>
#include <cstdint>
#include <span>

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/surface.vert and normal.frag.
constexpr GLint kViewProjection = 0;
constexpr GLint kEye = 1;
constexpr GLint kForward = 2;
constexpr GLint kLeaf = 3;
constexpr GLint kFirstTriangle = 4;
constexpr GLint kTileOrigin = 5;

}  // namespace

NormalPass::NormalPass()
    : program_(gpu::Program::fromFiles("normal", {"csg/surface.vert", "csg/normal.frag"})), target_("normal tile") {}

std::vector<LeafPixels> NormalPass::visibleLeaves(const FrameTargets& targets, const PixelRect& tile) {
    std::vector<std::int32_t> codes(static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height));
    targets.resultLeaf.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED_INTEGER, GL_INT,
                                      std::as_writable_bytes(std::span(codes)));
    std::vector<LeafPixels> leaves;
    std::vector<int> slot;  // leaf -> index in `leaves`, or -1
    for (int y = 0; y < tile.height; ++y) {
        for (int x = 0; x < tile.width; ++x) {
            const std::int32_t code = codes[static_cast<std::size_t>(y) * static_cast<std::size_t>(tile.width) +
                                            static_cast<std::size_t>(x)];
            if (code < 0) continue;
            const auto leaf = static_cast<std::size_t>(code >> 1);
            if (leaf >= slot.size()) slot.resize(leaf + 1, -1);
            if (slot[leaf] < 0) {
                slot[leaf] = static_cast<int>(leaves.size());
                leaves.push_back({static_cast<int>(leaf), {x, y, 1, 1}});
                continue;
            }
            PixelRect& r = leaves[static_cast<std::size_t>(slot[leaf])].rect;
            const int x1 = std::max(r.x + r.width, x + 1), y1 = std::max(r.y + r.height, y + 1);
            r.x = std::min(r.x, x);
            r.y = std::min(r.y, y);
            r.width = x1 - r.x;
            r.height = y1 - r.y;
        }
    }
    return leaves;
}

void NormalPass::run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
                     const std::vector<LeafPixels>& leaves) {
    if (leaves.empty()) return;
    if (!scratch_.id() || scratch_.width() < tile.width || scratch_.height() < tile.height) {
        scratch_ = gpu::Texture::create2D("normal tile", GL_RGBA32F, std::max(tile.width, scratch_.width()),
                                          std::max(tile.height, scratch_.height()));
        target_.attachTexture(GL_COLOR_ATTACHMENT0, scratch_);
        target_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
        target_.checkComplete();
    }
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glDisable(GL_SCISSOR_TEST);
    target_.clearColor(0, zero);

    program_.setUniform(kViewProjection, view.viewProjection);
    program_.setUniform(kEye, view.eye);
    program_.setUniform(kForward, view.forward);
    program_.setUniform(kTileOrigin, glm::ivec2(tile.x, tile.y));
    program_.use();
    targets.resultDepth.bindUnit(0);
    targets.resultLeaf.bindUnit(1);
    scene.faceNormals().bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    target_.bindForDraw();
    // The peel pass's viewport: the tile's pixels at the texture's origin.
    glViewport(-tile.x, -tile.y, view.width, view.height);
    glEnable(GL_SCISSOR_TEST);
    scene.vertexArray().bind();
    for (const LeafPixels& visible : leaves) {
        glScissor(visible.rect.x, visible.rect.y, visible.rect.width, visible.rect.height);
        program_.setUniform(kLeaf, visible.leaf);
        program_.setUniform(kFirstTriangle, static_cast<int>(scene.leaf(visible.leaf).firstTriangle));
        scene.drawLeaf(visible.leaf);
    }
    glDisable(GL_SCISSOR_TEST);
    glCopyImageSubData(scratch_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, targets.normal.id(), GL_TEXTURE_2D, 0, tile.x, tile.y,
                       0, tile.width, tile.height, 1);
    gpu::checkErrors();
}

}  // namespace strata::render
