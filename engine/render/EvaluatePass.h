#pragma once
// The evaluate pass: per tile, draws the blocks of the tile where the result
// can have a surface: each pixel merges the operands' peeled surfaces and
// walks them front to back (shaders/csg/evaluate.frag) to the first surface
// where the result's membership changes. Writes FrameTargets::resultDepth and
// resultLeaf, and marks the pixels it wrote in the stencil of
// FrameTargets::marks, inside the tile (FrameTargets::mark).
//
// The tree lives in storage buffers: a tree edit only re-uploads them. Each
// 16x16 block of a tile gets the tree specialised to the operands whose
// screen rectangle meets it (strata/csg/CompiledTree.h: specializeCode, then
// countingTree), so a pixel gathers and evaluates only what can matter there.
// The shader comes in four forms (BlockForm): the first-surface form (the
// block's tree is one operand of one layer, so the result's first surface is
// the operand's), the register form (up to eight operands of up to sixteen
// peeled layers in all, a slot per layer, the tree as a truth table,
// everything in registers; MAX_LIVE 4, 8 or 16 slots), the product form (more operands of one
// layer each under a single AND or OR: a CSG product or a union) and the
// array form (anything else: a heap of surfaces and a counting tree in
// per-pixel arrays of MAX_LIVE, a power of two from 16 up). A variant of the
// shader is a form with its MAX_LIVE; each block is drawn (runs of blocks
// along a row as one instanced quad) by the cheapest variant that holds it.
// A variant is compiled on first use and kept.
//
// GL state: sets the viewport, the stencil test and function; leaves the
// stencil test off. Expects blending, depth test and culling off.

#include <compare>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "FrameTargets.h"
#include "PeelPass.h"
#include "ShaderInterface.h"
#include "ViewSetup.h"
#include "strata/csg/CompiledTree.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/Frame.h"

namespace strata::render {

class EvaluatePass {
public:
    EvaluatePass();

    // Takes the compiled tree; its operand k is tree leaf tree.operandLeaf[k].
    // Compiles now the variants the tree will likely use, writing leaf
    // marks or not (`leafMarks`, as the frames will ask: FrameTargets::leafMarks).
    void setTree(const csg::CompiledTree& tree, bool leafMarks);

    // `rects[k]` is operand k's screen rectangle (frame pixels), and
    // `hulls[k]` its screen hull where it has one (screenBounds; missing or
    // empty: the rectangle alone): each 16x16 block's tree is specialised
    // to the operands whose rectangle and hull reach its pixels.
    // `generalOnly` draws every block with the array form (tests compare the
    // forms). Adds the blocks drawn in each form to `stats`, and where
    // `forms` is given sets it to each block's form (blocks of the tile
    // row by row from its lower-left corner, kBlock pixels square).
    // `groupTable` (groupTable() below) and `groupIds` (PeelPass::groupIds,
    // no texture without groups) name the member of a group that makes a surface.
    void run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
             const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
             const std::vector<ScreenHull>& hulls, const std::vector<int>& groupTable, const gpu::Texture& groupIds, bool generalOnly, double coincidence,
             FrameStats& stats, std::vector<BlockForm>* forms = nullptr);

    // One round of peeling the result (Renderer::sampleResult): as run(),
    // but each pixel reports the first change of the result after the
    // surface that `start` holds for it (a frame-sized R32F texture of
    // tagged depths: -inf for the first round, +inf where a ray is done).
    // Only the register and array forms walk on past a start. `samePlan`:
    // the tile and its layers are those of the round before, whose block
    // plan is reused.
    void runResultRound(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                        const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
                        const std::vector<ScreenHull>& hulls, const std::vector<int>& groupTable, const gpu::Texture& groupIds, const gpu::Texture& start,
                        bool samePlan, double coincidence, FrameStats& stats);

    // The tile's groups of convex operands for run() (evaluate.frag:
    // groupTable): per tree leaf (`leafCount`) -1, or for a group's operand
    // leaf where its record starts: the group's layer of PeelPass::groupIds
    // (`layers[k].idsLayer`), then its members (csg::CompiledTree::operandGroups).
    static std::vector<int> groupTable(std::size_t leafCount, const csg::CompiledTree& tree,
                                       const std::vector<OperandLayers>& layers);

    // The array form's MAX_LIVE for `count` literals or nodes: a power of
    // two, at least 16.
    static int capacityFor(int count);

    // Per tree leaf, after run(): which of its faces the result shows in the
    // tile, kFrontFaces | kBackFaces (0: none) where the leaf is the result's
    // own surface, the same shifted by kFlipped where it acts subtracted (its
    // normal flipped): bit shader::faceBit(exit, flip). Waits for the GPU.
    std::vector<std::uint32_t> shownFaces() const;
    static constexpr std::uint32_t kFrontFaces = 1u << shader::faceBit(false, false);
    static constexpr std::uint32_t kBackFaces = 1u << shader::faceBit(true, false);
    static constexpr int kFlipped = shader::faceBit(false, true);
    // The most slots of the register form (compiled for MAX_LIVE 4, 8 and
    // 16): up to this many peeled layers of the block's operands, of at most
    // kRegisterOperands operands (the truth table's inputs).
    static constexpr int kRegisterSlots = 16;
    static constexpr int kRegisterOperands = 8;
    // The array form's largest MAX_LIVE compiled with the tree (setTree).
    static constexpr int kPrecompiledLive = 64;
    static constexpr int kBlock = shader::kBlock;

private:
    // A variant of evaluate.frag: its form and, for the register and array
    // forms, its MAX_LIVE.
    struct Variant {
        BlockForm form = BlockForm::None;  // None: the result is constant, nothing to draw
        int maxLive = 0;
        auto operator<=>(const Variant&) const = default;
    };
    // A block's tree as the shader reads it: the block's record (blocks.glsl)
    // and the variant that draws it.
    struct BlockTree {
        glm::uvec4 record{0u};
        Variant variant;
    };
    // Where a block tree's data goes: the literals (or slots) and the inner
    // nodes of every tree of the tile, one after the other.
    struct TreeData {
        std::vector<glm::uvec4> literals;
        std::vector<glm::uvec4> nodes;
    };
    // What one tile draws: every block's record, the runs of blocks each
    // variant draws (one instanced quad per run), and the leaves whose front
    // faces count as shown beforehand.
    struct BlockPlan {
        int blocksX = 0;
        std::vector<glm::uvec4> blocks;
        TreeData data;
        std::map<Variant, std::vector<std::uint32_t>> blocksOf;  // per variant, its blocks
        std::vector<glm::uvec2> runs;                            // first block, blocks in the run
        std::map<Variant, std::size_t> runsOf;                   // per variant, its runs (in order)
        std::vector<std::uint32_t> shownBefore;                  // per tree leaf
    };

    // The tile's blocks: each one's tree, record and variant (the part of
    // run() that decides; draw() is the part that draws).
    // `forms`: which forms a block may take.
    enum class Forms { Any, WalkOn, ArrayOnly };
    BlockPlan planBlocks(const FrameTargets& targets, const PixelRect& tile,
                         const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
                         const std::vector<ScreenHull>& hulls, const std::vector<int>& groupTable,
                         Forms forms) const;
    // Per block of the tile (`blocksX` per row), the operands whose rectangle
    // meets it and whose hull (where it has one) reaches its pixel centres.
    std::vector<std::vector<std::uint32_t>> operandsPerBlock(const PixelRect& tile, int blocksX,
                                                             const std::vector<OperandLayers>& operandLayers,
                                                             const std::vector<PixelRect>& rects,
                                                             const std::vector<ScreenHull>& hulls) const;
    // Uploads `plan`, binds the pass's inputs and draws each variant's runs.
    // `start`: the result peel's start texture (runResultRound), or null.
    void draw(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile, const BlockPlan& plan,
              const std::vector<int>& groupTable, const gpu::Texture& groupIds, double coincidence,
              FrameStats& stats, const gpu::Texture* start = nullptr);

    // Appends the data of `code` (specialised code) to `data` in the
    // cheapest of the `forms` that holds it.
    BlockTree addTree(const std::vector<std::uint32_t>& code, const std::vector<OperandLayers>& operandLayers,
                      TreeData& data, Forms forms) const;
    // One per form: the operands `used` that `code` reads, each once, of
    // `slots` layers in all.
    BlockTree firstSurfaceTree(std::uint32_t operand, const std::vector<OperandLayers>& operandLayers) const;
    BlockTree registerTree(const std::vector<std::uint32_t>& code, const std::vector<std::uint32_t>& used, int slots,
                           const std::vector<OperandLayers>& operandLayers, TreeData& data) const;
    BlockTree productTree(const csg::CountingTree& tree, const std::vector<OperandLayers>& operandLayers,
                          TreeData& data) const;
    BlockTree arrayTree(const csg::CountingTree& tree, const std::vector<std::uint32_t>& used,
                        const std::vector<OperandLayers>& operandLayers, TreeData& data) const;

    // The compiled variant; `leafMarks`: it writes FrameTargets::mark(leaf,
    // exit, flip) to the stencil; `resultPeel`: it walks on past a start;
    // `plainBeside`: it writes only where its surface is shown before the
    // plain leaves' (FrameTargets::plainBeside).
    gpu::Program& programFor(Variant variant, bool leafMarks, bool resultPeel = false, bool plainBeside = false);

    struct ProgramKey {
        Variant variant;
        bool leafMarks = false;
        bool groups = false;
        bool resultPeel = false;
        bool plainBeside = false;
        auto operator<=>(const ProgramKey&) const = default;
    };
    std::map<ProgramKey, gpu::Program> variants_;
    bool groups_ = false;  // the tree has groups of convex operands (GROUPS variants)
    csg::CompiledTree tree_;
    gpu::Buffer blocks_;
    gpu::Buffer blockOperands_;
    gpu::Buffer blockNodes_;
    gpu::Buffer drawnBlocks_;
    gpu::Buffer shownFaces_;  // per tree leaf, see shownFaces()
    gpu::Buffer groupTable_;
    std::size_t leafCount_ = 0;
    std::vector<int> operandLeaf_;
    gpu::VertexArray empty_;
    BlockPlan roundPlan_;  // runResultRound's plan, kept for the rounds after the first
};

}  // namespace strata::render
