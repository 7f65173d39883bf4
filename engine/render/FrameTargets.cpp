#include "FrameTargets.h"

#include "strata/core/Error.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>

namespace strata::render {

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
    shownDepth = {};
    plainShownTarget = {};
    plainShownLitTarget = {};
    resultDepth = gpu::Texture::create2D("result depth", GL_R32F, width, height);
    resultLeaf = gpu::Texture::create2D("result leaf", GL_R32I, width, height);
    normal = gpu::Texture::create2D("result normal", GL_RGBA32F, width, height);
    color = gpu::Texture::create2D("colour", GL_RGBA8, width, height);
    marks = gpu::Texture::create2D("marks", GL_STENCIL_INDEX8, width, height);

    evaluateTarget = gpu::Framebuffer("evaluate");
    evaluateTarget.attachTexture(GL_COLOR_ATTACHMENT0, resultDepth);
    evaluateTarget.attachTexture(GL_COLOR_ATTACHMENT1, resultLeaf);
    evaluateTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
    evaluateTarget.attachTexture(GL_STENCIL_ATTACHMENT, marks);
    evaluateTarget.checkComplete();

    normalTarget = gpu::Framebuffer("normal");
    normalTarget.attachTexture(GL_COLOR_ATTACHMENT0, normal);
    normalTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    normalTarget.attachTexture(GL_STENCIL_ATTACHMENT, marks);
    normalTarget.checkComplete();

    colorTarget = gpu::Framebuffer("colour");
    colorTarget.attachTexture(GL_COLOR_ATTACHMENT0, color);
    colorTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    colorTarget.setReadBuffer(GL_COLOR_ATTACHMENT0);
    colorTarget.attachTexture(GL_STENCIL_ATTACHMENT, marks);
    colorTarget.checkComplete();
}

void FrameTargets::ensurePlain() {
    if (plainDepth.id() != 0) return;
    plainDepth = gpu::Texture::create2D("plain depth", GL_DEPTH32F_STENCIL8, width_, height_);
    plainTarget = gpu::Framebuffer("plain");
    plainTarget.attachTexture(GL_COLOR_ATTACHMENT0, resultDepth);
    plainTarget.attachTexture(GL_COLOR_ATTACHMENT1, resultLeaf);
    plainTarget.attachTexture(GL_COLOR_ATTACHMENT2, normal);
    plainTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
    plainTarget.attachTexture(GL_DEPTH_STENCIL_ATTACHMENT, plainDepth);
    plainTarget.checkComplete();

    plainLitTarget = gpu::Framebuffer("plain lit");
    plainLitTarget.attachTexture(GL_COLOR_ATTACHMENT0, resultDepth);
    plainLitTarget.attachTexture(GL_COLOR_ATTACHMENT1, resultLeaf);
    plainLitTarget.attachTexture(GL_COLOR_ATTACHMENT2, normal);
    plainLitTarget.attachTexture(GL_COLOR_ATTACHMENT3, color);
    plainLitTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3});
    plainLitTarget.attachTexture(GL_DEPTH_STENCIL_ATTACHMENT, plainDepth);
    plainLitTarget.checkComplete();

    plainColorTarget = gpu::Framebuffer("plain colour");
    plainColorTarget.attachTexture(GL_COLOR_ATTACHMENT0, color);
    plainColorTarget.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    plainColorTarget.setReadBuffer(GL_COLOR_ATTACHMENT0);
    plainColorTarget.attachTexture(GL_STENCIL_ATTACHMENT, plainDepth);
    plainColorTarget.checkComplete();
}

void FrameTargets::ensureShown() {
    if (shownDepth.id() != 0) return;
    ensurePlain();
    shownDepth = gpu::Texture::create2D("shown depth", GL_DEPTH_COMPONENT32F, width_, height_);
    auto make = [&](gpu::Framebuffer& target, const char* name, const gpu::Texture& shown, GLenum depthAttachment,
                    const gpu::Texture& depth) {
        target = gpu::Framebuffer(name);
        target.attachTexture(GL_COLOR_ATTACHMENT0, shown);
        target.attachTexture(GL_COLOR_ATTACHMENT1, resultDepth);
        target.attachTexture(GL_COLOR_ATTACHMENT2, resultLeaf);
        target.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
        target.attachTexture(depthAttachment, depth);
        target.checkComplete();
    };
    make(plainShownTarget, "plain shown", normal, GL_DEPTH_STENCIL_ATTACHMENT, plainDepth);
    make(plainShownLitTarget, "plain shown lit", color, GL_DEPTH_ATTACHMENT, shownDepth);
}

void FrameTargets::clearResult(bool wholeFrame, bool wholeNormal, const PixelRect& drawn) {
    glDisable(GL_SCISSOR_TEST);
    if (wholeFrame) {
        const float depth[4] = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
        const GLint leaf[4] = {shader::kLeafMiss, 0, 0, 0};
        evaluateTarget.clearColor(0, depth);
        evaluateTarget.clearColorInt(1, leaf);
    }
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (wholeNormal) normalTarget.clearColor(0, zero);
    const PixelRect r = drawn.intersection({0, 0, width_, height_});
    if (r.empty()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.width, r.height);
    if (!wholeNormal) normalTarget.clearColor(0, zero);
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
