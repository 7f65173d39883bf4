#include "FrameTargets.h"

#include "strata/core/Error.h"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

namespace strata::render {

namespace {

// A framebuffer that draws into `colors` (colour attachment k holds
// colors[k], every one a draw buffer, the first the read buffer), with
// `depth` at `depthAttachment` (depth, stencil or both).
gpu::Framebuffer framebufferOf(const char* name, std::initializer_list<const gpu::Texture*> colors,
                               GLenum depthAttachment, const gpu::Texture& depth) {
    gpu::Framebuffer target(name);
    std::vector<GLenum> buffers;
    for (const gpu::Texture* texture : colors) {
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
        target.attachTexture(attachment, *texture);
        buffers.push_back(attachment);
    }
    target.setDrawBuffers(std::span<const GLenum>(buffers));
    target.setReadBuffer(GL_COLOR_ATTACHMENT0);
    target.attachTexture(depthAttachment, depth);
    target.checkComplete();
    return target;
}

}  // namespace

void FrameTargets::ensure(int width, int height) {
    if (width == width_ && height == height_) return;
    try {
        allocate(width, height);
    } catch (const Error&) {
        // What fails at this size is the memory (a driver reports it as an
        // incomplete framebuffer, or an out-of-memory error): say so, once.
        *this = FrameTargets{};
        const double mebibytes = static_cast<double>(width) * height * kBytesPerPixel / (1024.0 * 1024.0);
        char text[160];
        std::snprintf(text, sizeof text, "renderer: not enough memory for a %d x %d image (its targets take %.0f MiB)",
                      width, height, mebibytes);
        throw Error(text);
    }
    width_ = width;
    height_ = height;
}

void FrameTargets::allocate(int width, int height) {
    plainDepth = {};
    plainTarget = {};
    plainLitTarget = {};
    plainColorTarget = {};
    plainEvaluateTarget = {};
    plainNormalTarget = {};
    shownDepth = {};
    plainShownTarget = {};
    plainShownLitTarget = {};
    resultDepth = gpu::Texture::create2D("result depth", GL_R32F, width, height);
    resultLeaf = gpu::Texture::create2D("result leaf", GL_R32I, width, height);
    normal = gpu::Texture::create2D("result normal", GL_RGBA32F, width, height);
    color = gpu::Texture::create2D("colour", GL_RGBA8, width, height);
    marks = gpu::Texture::create2D("marks", GL_STENCIL_INDEX8, width, height);
    evaluateTarget = framebufferOf("evaluate", {&resultDepth, &resultLeaf}, GL_STENCIL_ATTACHMENT, marks);
    normalTarget = framebufferOf("normal", {&normal}, GL_STENCIL_ATTACHMENT, marks);
    colorTarget = framebufferOf("colour", {&color}, GL_STENCIL_ATTACHMENT, marks);
}

void FrameTargets::ensurePlain() {
    if (plainDepth.id() != 0) return;
    plainDepth = gpu::Texture::create2D("plain depth", GL_DEPTH32F_STENCIL8, width_, height_);
    plainTarget = framebufferOf("plain", {&resultDepth, &resultLeaf, &normal}, GL_DEPTH_STENCIL_ATTACHMENT, plainDepth);
    plainLitTarget =
        framebufferOf("plain lit", {&resultDepth, &resultLeaf, &normal, &color}, GL_DEPTH_STENCIL_ATTACHMENT, plainDepth);
    plainColorTarget = framebufferOf("plain colour", {&color}, GL_STENCIL_ATTACHMENT, plainDepth);
    plainEvaluateTarget =
        framebufferOf("evaluate beside plain", {&resultDepth, &resultLeaf}, GL_STENCIL_ATTACHMENT, plainDepth);
    plainNormalTarget = framebufferOf("normal beside plain", {&normal}, GL_STENCIL_ATTACHMENT, plainDepth);
}

void FrameTargets::ensureShown() {
    if (shownDepth.id() != 0) return;
    ensurePlain();
    shownDepth = gpu::Texture::create2D("shown depth", GL_DEPTH_COMPONENT32F, width_, height_);
    plainShownTarget = framebufferOf("plain shown", {&normal, &resultDepth, &resultLeaf}, GL_DEPTH_STENCIL_ATTACHMENT,
                                     plainDepth);
    plainShownLitTarget =
        framebufferOf("plain shown lit", {&color, &resultDepth, &resultLeaf}, GL_DEPTH_ATTACHMENT, shownDepth);
}

void FrameTargets::clearResult(bool wholeFrame, NormalClear normals, const PixelRect& drawn) {
    glDisable(GL_SCISSOR_TEST);
    if (wholeFrame) {
        const float depth[4] = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
        const GLint leaf[4] = {shader::kLeafMiss, 0, 0, 0};
        evaluateTarget.clearColor(0, depth);
        evaluateTarget.clearColorInt(1, leaf);
    }
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (normals == NormalClear::WholeFrame) normalTarget.clearColor(0, zero);
    const PixelRect r = drawn.intersection({0, 0, width_, height_});
    if (r.empty()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.width, r.height);
    if (normals == NormalClear::Drawn) normalTarget.clearColor(0, zero);
    const GLint noMark = 0;
    glClearNamedFramebufferiv(evaluateTarget.id(), GL_STENCIL, 0, &noMark);
    glDisable(GL_SCISSOR_TEST);
}

void FrameTargets::clearRegion(const PixelRect& region) {
    const PixelRect r = region.intersection({0, 0, width_, height_});
    if (r.empty()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.width, r.height);
    const float depth[4] = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
    const GLint leaf[4] = {shader::kLeafMiss, 0, 0, 0};
    evaluateTarget.clearColor(0, depth);
    evaluateTarget.clearColorInt(1, leaf);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    normalTarget.clearColor(0, zero);
    const GLint noMark = 0;
    glClearNamedFramebufferiv(evaluateTarget.id(), GL_STENCIL, 0, &noMark);
    glDisable(GL_SCISSOR_TEST);
}

namespace {

// The greedy colouring below compares each operand with every one placed
// before it: quadratic, so kept to scenes where that is cheap.
constexpr std::size_t kMaxGreedyOperands = 4096;

}  // namespace

void FrameTargets::assignMarkSlots(std::span<const int> operandLeaves, std::span<const PixelRect> rects,
                                   std::size_t leafCount) {
    markSlots_.assign(std::max<std::size_t>(leafCount, 1), 0);
    const std::size_t n = operandLeaves.size();
    if (n <= static_cast<std::size_t>(kMarkSlots)) {
        for (std::size_t k = 0; k < n; ++k) markSlots_[static_cast<std::size_t>(operandLeaves[k])] = static_cast<int>(k);
    } else if (n > kMaxGreedyOperands) {
        // Past a few thousand operands most slots are shared within any
        // rectangle anyway (the normal pass then checks every mark): deal
        // them out in turn, in linear time, rather than colouring.
        for (std::size_t k = 0; k < n; ++k)
            markSlots_[static_cast<std::size_t>(operandLeaves[k])] = static_cast<int>(k % kMarkSlots);
    } else {
        // Greedy colouring of the rectangles' overlap graph, largest first:
        // the big operands (a cheese's cube) overlap the most and choose first.
        auto area = [&](std::size_t k) {
            return static_cast<std::size_t>(std::max(rects[k].width, 0)) *
                   static_cast<std::size_t>(std::max(rects[k].height, 0));
        };
        std::vector<std::size_t> order(n);
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return area(a) > area(b); });
        std::vector<int> slotOf(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t k = order[i];
            int sharing[kMarkSlots] = {};
            for (std::size_t j = 0; j < i; ++j) {
                const std::size_t o = order[j];
                if (rects[o].intersects(rects[k])) ++sharing[slotOf[o]];
            }
            slotOf[k] = static_cast<int>(std::min_element(sharing, sharing + kMarkSlots) - sharing);
            markSlots_[static_cast<std::size_t>(operandLeaves[k])] = slotOf[k];
        }
    }
    gpu::Buffer::uploadGrowing(markSlotBuffer_, "mark slots", markSlots_);
}

bool FrameTargets::canMarkLeaves() {
    return epoxy_has_gl_extension("GL_ARB_shader_stencil_export");
}

std::size_t FrameTargets::bytes() const {
    return resultDepth.byteSize() + resultLeaf.byteSize() + normal.byteSize() + color.byteSize() + marks.byteSize() +
           (plainDepth.id() != 0 ? plainDepth.byteSize() : 0) + (shownDepth.id() != 0 ? shownDepth.byteSize() : 0);
}

}  // namespace strata::render
