#pragma once
// The evaluate pass: one fullscreen draw per tile that merges the operands'
// peeled surfaces per pixel and runs the compiled tree program
// (shaders/csg/evaluate.frag) to find the first surface where the result's
// membership changes. Writes FrameTargets::resultDepth and resultLeaf inside
// the tile.
//
// The program and the operand table live in storage buffers: a tree edit only
// re-uploads them. Each 16x16 block of a tile gets the list of operands whose
// screen rectangle meets it and the program specialised to them, so a pixel
// gathers and evaluates only what can matter there. The shader is specialised
// only by the sizes of its per-pixel arrays: MAX_OPERANDS (one state bit per
// operand) and MAX_LIVE (the longest block list), each rounded up to a power
// of two; a variant is compiled on first use and kept.
//
// GL state: sets the viewport to the tile; expects blending, depth test,
// culling and the scissor test off.

#include <map>
#include <vector>

#include "FrameTargets.h"
#include "PeelPass.h"
#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/TreeProgram.h"

namespace strata::render {

class EvaluatePass {
public:
    EvaluatePass();

    // Uploads the program; operand k of it is tree leaf program.operandLeaf[k].
    void setProgram(const TreeProgram& program);

    // `rects[k]` is operand k's screen rectangle (frame pixels): the shader
    // gathers, per 16x16 block, only the operands whose rectangle meets it.
    void run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
             const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects);

    // A per-pixel array size for `count` entries: a power of two, at least 16.
    static int capacityFor(int count);
    static constexpr int kBlock = 16;  // BLOCK in evaluate.frag
    // Per-pixel head arrays are never sized below this (or the operand
    // count), so small scenes need a single shader variant.
    static constexpr int kMinLive = 64;

private:
    gpu::Program& programFor(int operands, int live);

    std::map<std::pair<int, int>, gpu::Program> programs_;  // by (MAX_OPERANDS, MAX_LIVE)
    TreeProgram program_;
    gpu::Buffer table_;
    gpu::Buffer blocks_;
    gpu::Buffer blockOperands_;
    gpu::Buffer blockCode_;
    std::vector<int> operandLeaf_;
    gpu::VertexArray empty_;
};

}  // namespace strata::render
