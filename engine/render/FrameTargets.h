#pragma once
// The full-frame images the passes hand to each other (the G-buffer) and the
// final colour, with a framebuffer per pass that writes them.
//
//   resultDepth  R32F     tagged view depth of the visible surface, +inf on a miss   (evaluate)
//   resultLeaf   R32I     shader::leafCode(leaf, flip), kLeafMiss on a miss          (evaluate)
//   normal       RGBA32F  xyz the world-space outward normal of the result, w its     (normal)
//                         base colour (ShadePass::packBaseColor); 0 on a miss
//   color        RGBA8    the shaded image                                     (shade, alpha, translucent)
//   marks        S8       stencil: mark(leaf, exit, flip) where the evaluator     (evaluate)
//                         found a surface of that leaf, else 0
//
// The later passes test the stencil so that they run only where there is
// something to do: a fragment that fails the stencil test never runs its
// shader, on llvmpipe as on GPUs, while a shader that branches to skip work
// costs almost as much as doing it on llvmpipe (it runs both sides of every
// branch for its 8 or 16 lanes). Where the driver lets a fragment shader
// write the stencil value (ARB_shader_stencil_export), the mark names the
// leaf's mark slot, the facing of its surface there and whether the leaf
// acts subtracted (shader::stencilMark; evaluate.frag writes it from the
// slots buffer), so the normal pass, drawing one leaf at a time, skips the
// other leaves' pixels before its shader runs. The 8-bit stencil holds 63
// slots: up to 63 operands each has its own, and past that leaves whose
// screen rectangles overlap get different slots where the 63 allow
// (assignMarkSlots); elsewhere every written pixel gets shader::kMarkWritten
// (and the evaluator's pixels it could not finish get it too, where with
// leaf marks they get 0).

#include <cstddef>
#include <span>
#include <vector>

#include "ShaderInterface.h"
#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"

namespace strata::render {

class FrameTargets {
public:
    // (Re)creates the images when the size changes. Throws strata::Error
    // "renderer: not enough memory for a W x H image (...)" when they cannot
    // be made, and is then empty again.
    void ensure(int width, int height);
    // Which normals a frame clears: none (no pass reads them: the normal
    // pass lights its surfaces as drawn), those inside `drawn`, or all.
    enum class NormalClear { None, Drawn, WholeFrame };
    // Sets pixels to "miss": marks 0 inside `drawn`; where `wholeFrame`,
    // depth +inf and leaf -1 everywhere; normal 0 where `normals` says. The
    // passes read the marks only where an operand can be drawn, depth and
    // leaf only where the evaluator marked a pixel this frame, and the shade
    // pass reads normals there and at their eight neighbours. So `drawn`
    // need only hold every pixel the evaluator may mark and a pixel around
    // them; depth and leaf need clearing everywhere only for their read-back
    // or a pass that reads every pixel (translucent, alpha), and normals
    // only for their read-back: clearing the RGBA32F normals of a whole
    // 1024 x 768 frame costs llvmpipe about 3 ms of CPU.
    void clearResult(bool wholeFrame, NormalClear normals, const PixelRect& drawn);
    // Every target of the evaluate and normal passes cleared inside `region`
    // only (a round of the result peel over one tile).
    void clearRegion(const PixelRect& region);

    int width() const { return width_; }
    int height() const { return height_; }
    std::size_t bytes() const;

    gpu::Texture resultDepth, resultLeaf, normal, color, marks;
    // Each with `marks` as its stencil.
    gpu::Framebuffer evaluateTarget;  // 0: resultDepth, 1: resultLeaf
    gpu::Framebuffer normalTarget;    // 0: normal
    gpu::Framebuffer colorTarget;     // 0: color

    // The plain path's (PlainPass.h) depth and stencil, D32F_S8: its depth
    // test, and the marks of the pixels it wrote, which the shade pass then
    // tests in place of `marks`. Made by ensurePlain, at the first plain
    // frame of a size.
    gpu::Texture plainDepth;
    gpu::Framebuffer plainTarget;       // 0: resultDepth, 1: resultLeaf, 2: normal; plainDepth
    gpu::Framebuffer plainLitTarget;    // the same and 3: color (a plain frame lit as drawn)
    gpu::Framebuffer plainColorTarget;  // 0: color; plainDepth's stencil
    void ensurePlain();  // also plainEvaluateTarget and plainNormalTarget
    // A plain frame that is only shown (Renderer::renderInto, nothing read
    // back and no pass after it that reads the G-buffer) writes only what
    // the image needs, into one of two targets, each 0: what the frame
    // shows, 1: resultDepth (the tie pass's input), 2: resultLeaf (drawn
    // only where a pass reads them after: PlainPass::Output::keepResult). plainShownLitTarget: 0 `color`, lit as drawn, and shownDepth,
    // D32F with no stencil (no pass after it); plainShownTarget: 0
    // `normal`, for the shade pass's outline, and plainDepth, whose marks
    // the shade pass tests. Made by ensureShown (with ensurePlain's).
    gpu::Texture shownDepth;
    gpu::Framebuffer plainShownTarget, plainShownLitTarget;
    void ensureShown();
    // This frame's choice, set by the renderer: the marks are plainDepth's.
    bool plainFrame = false;
    // This frame's choice, set by the renderer: plain leaves were drawn
    // beside the CSG (PlainPass.h, Output::beside) into resultDepth and
    // resultLeaf before the evaluator, which writes only where its surface
    // is shown before theirs.
    bool plainBeside = false;
    // This frame's choice, set by the renderer: the plain pass marked the
    // pixels it drew, for the shade pass, in plainDepth's stencil, so the
    // evaluator's marks go there too, and the evaluate and normal passes
    // draw through the targets below.
    bool plainMarks = false;
    gpu::Framebuffer plainEvaluateTarget;  // evaluateTarget's images, plainDepth's stencil
    gpu::Framebuffer plainNormalTarget;    // normalTarget's, plainDepth's stencil
    // The colour image with this frame's marks as its stencil.
    const gpu::Framebuffer& shadeTarget() const { return plainFrame || plainMarks ? plainColorTarget : colorTarget; }
    // The evaluate and normal passes' targets with this frame's marks.
    const gpu::Framebuffer& evaluateFramebuffer() const { return plainMarks ? plainEvaluateTarget : evaluateTarget; }
    const gpu::Framebuffer& normalFramebuffer() const { return plainMarks ? plainNormalTarget : normalTarget; }

    // Whether the driver can give each pixel its leaf's mark (asks GL).
    static bool canMarkLeaves();
    // This frame's choice, set by the renderer before the evaluate pass.
    bool leafMarks = false;
    static constexpr int kMarkSlots = shader::kMarkSlots;  // 4 marks each, 1..252
    // Gives each leaf the evaluator may write (tree leaf operandLeaves[k]:
    // the operands, and for a group of convex operands its members; screen
    // rectangle rects[k]) a mark slot, and uploads them (the evaluator's
    // storage buffer 1): slot k while there are at most kMarkSlots of them;
    // past that, largest rectangle first, the slot fewest of the overlapping
    // ones already placed have taken (the lowest of those). Other leaves get
    // slot 0. Call before the evaluate pass.
    void assignMarkSlots(std::span<const int> operandLeaves, std::span<const PixelRect> rects, std::size_t leafCount);
    int markSlot(int leaf) const { return markSlots_[static_cast<std::size_t>(leaf)]; }
    const gpu::Buffer& markSlotBuffer() const { return markSlotBuffer_; }
    // The stencil value of a pixel showing `leaf`'s front face (its back
    // face: `exit`), flipped (the leaf acts subtracted there) or not.
    int mark(int leaf, bool exit, bool flip) const {
        return leafMarks ? shader::stencilMark(markSlot(leaf), shader::faceBit(exit, flip)) : shader::kMarkWritten;
    }

private:
    // depth 4, leaf 4, normal 16, colour 4, marks 1
    static constexpr double kBytesPerPixel = 29;
    void allocate(int width, int height);
    int width_ = 0, height_ = 0;
    std::vector<int> markSlots_;  // per tree leaf
    gpu::Buffer markSlotBuffer_;
};

}  // namespace strata::render
