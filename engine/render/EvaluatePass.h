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
// screen rectangle meets it (TreeProgram.h: specializeProgram, then
// countingTree), so a pixel gathers and evaluates only what can matter there.
// The shader comes in four forms: the first-surface form (the block's tree
// is one operand of one layer, so the result's first surface is the
// operand's), the register form (operands of up to eight peeled layers in
// all, a slot per layer, the tree as a truth table, everything in
// registers; MAX_LIVE 4 or 8 slots), the product form (more
// operands of one layer each under a single AND or OR: a CSG product or a
// union) and the array form (anything else: a heap of surfaces and a
// counting tree in per-pixel arrays of MAX_LIVE, a power of two from 16 up).
// Each block is drawn (one instanced quad per block) by the cheapest variant
// that holds it. A variant is compiled on first use and kept.
//
// GL state: sets the viewport, the stencil test and function; leaves the
// stencil test off. Expects blending, depth test and culling off.

#include <cstdint>
#include <map>
#include <vector>

#include <glm/vec4.hpp>

#include "FrameTargets.h"
#include "PeelPass.h"
#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/Renderer.h"
#include "strata/render/TreeProgram.h"

namespace strata::render {

class EvaluatePass {
public:
    EvaluatePass();

    // Uploads the program; operand k of it is tree leaf program.operandLeaf[k].
    // Compiles now the variants the program will likely use, writing leaf
    // marks or not (`leafMarks`, as the frames will ask: FrameTargets::leafMarks).
    void setProgram(const TreeProgram& program, bool leafMarks);

    // `rects[k]` is operand k's screen rectangle (frame pixels): the shader
    // gathers, per 16x16 block, only the operands whose rectangle meets it.
    // `generalOnly` draws every block with the array form (tests compare the
    // forms). Adds the blocks drawn in each form to `stats`, and where
    // `forms` is given sets it to each block's form (blocks of the tile
    // row by row from its lower-left corner, kBlock pixels square).
    // `groupTable` (groupTable() below) and `groupIds` (PeelPass::groupIds,
    // no texture without groups) name the member of a group that makes a surface.
    void run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
             const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
             const std::vector<int>& groupTable, const gpu::Texture& groupIds, bool generalOnly, FrameStats& stats,
             std::vector<BlockForm>* forms = nullptr);

    // The tile's groups of convex operands for run() (evaluate.frag:
    // groupTable): per tree leaf (`leafCount`) -1, or for a group's operand
    // leaf where its record starts: the group's layer of PeelPass::groupIds
    // (`layers[k].group`), then its members (TreeProgram::operandGroups).
    static std::vector<int> groupTable(std::size_t leafCount, const TreeProgram& program,
                                       const std::vector<OperandLayers>& layers);

    // The array form's size (MAX_LIVE) for `count` literals or nodes: a power
    // of two, at least 16.
    static int capacityFor(int count);

    // Per tree leaf, after run(): which of its faces the result shows in the
    // tile, kFrontFaces | kBackFaces (0: none) where the leaf is the result's
    // own surface, the same shifted by kFlipped where it acts subtracted (its
    // normal flipped). Waits for the GPU.
    std::vector<std::uint32_t> shownFaces() const;
    static constexpr std::uint32_t kFrontFaces = 1, kBackFaces = 2;
    static constexpr int kFlipped = 2;
    // The largest MAX_LIVE of evaluate.frag's register form (compiled for 4
    // and 8): up to this many peeled layers of the block's operands, the
    // tree as a truth table.
    static constexpr int kRegisterForm = 8;
    // The product and first-surface forms' variant keys (they have no
    // MAX_LIVE: they keep no arrays).
    static constexpr int kProductForm = 1;
    static constexpr int kFirstSurfaceForm = 2;
    static constexpr int kBlock = 16;  // BLOCK in evaluate.frag

private:
    struct BlockTree {
        glm::uvec4 record{0u};  // the block's entry in `blocks` (evaluate.frag)
        int form = 0;           // shader variant (MAX_LIVE, kProductForm or kFirstSurfaceForm); 0: constant result, nothing to draw
    };
    // Appends the block data of `code` (a specialised program) to `literals`
    // and `nodes`, in the first-surface, register or product form where it
    // fits (unless `generalOnly`), else the array form.
    BlockTree addTree(const std::vector<std::uint32_t>& code, const std::vector<OperandLayers>& operandLayers,
                      std::vector<glm::uvec4>& literals, std::vector<glm::uvec4>& nodes, bool generalOnly) const;
    // The form a shader variant (BlockTree::form, not 0) draws.
    static BlockForm blockForm(int variant);
    // `form`: 4, kRegisterForm, kProductForm, kFirstSurfaceForm or a
    // capacityFor() value; `leafMarks`: the shader writes
    // FrameTargets::mark(leaf, exit, flip) to the stencil.
    gpu::Program& programFor(int form, bool leafMarks);

    std::map<int, gpu::Program> programs_;  // by (form (BlockTree::form) * 2 + leaf marks) * 2 + groups_
    bool groups_ = false;  // the program has groups of convex operands (GROUPS variants)
    TreeProgram program_;
    gpu::Buffer blocks_;
    gpu::Buffer blockOperands_;
    gpu::Buffer blockNodes_;
    gpu::Buffer drawnBlocks_;
    gpu::Buffer shownFaces_;  // per tree leaf, see shownFaces()
    gpu::Buffer groupTable_;
    std::size_t leafCount_ = 0;
    std::vector<int> operandLeaf_;
    gpu::VertexArray empty_;
};

}  // namespace strata::render
