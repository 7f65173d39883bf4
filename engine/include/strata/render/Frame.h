#pragma once
// What a frame is asked and what it gives back: the settings of a frame, its
// figures, and the images read back. Plain structs, no GL: the renderer's
// facade (strata/render/Renderer.h), its passes and the --stats writer
// (strata/io/Stats.h) read them.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/render/ColorScheme.h"

namespace strata::render {

struct RenderSettings {
    // Dual-peel passes per operand; 0 = auto (until no surface is left).
    // A convex operand (cube, sphere, cylinder, convex polyhedron) always
    // takes one: it has at most two surfaces on any ray. So does one that
    // only unions lead to, seen from outside the model: its nearest surface
    // is all the result can show of it (docs/algorithm.md).
    int layers = 0;
    std::string colorScheme = "Cornfield";     // OpenSCAD colour scheme name
    Lighting lighting = Lighting::Strata;      // how the visible surface is lit
    // Darken creases and silhouettes: a Sobel filter on the normals, nine
    // taps a pixel in the shade pass. OpenSCAD's preview has no outline.
    bool outline = true;
    // Bytes the layered textures may take; above it the frame is rendered in
    // screen tiles (FrameStats::tiles, ::notes). Too small for a 16x16 tile:
    // strata::Error. Unset: the device's (Renderer::deviceSettings): an
    // eighth of a GPU's memory, from 512 MiB to 4 GiB, where its driver
    // tells it (NVIDIA's and AMD's); else 512 MiB (budget()).
    std::optional<std::size_t> memoryBudget;
    // Within the budget, layers of more bytes than this are drawn in tiles
    // where the operands are small on screen: quarters of the frame (then
    // quarters of those, down to 64 pixels a side) while a quarter's layers
    // hold only the operands that meet it and each step's tiles together
    // draw at most coverageTilingDraws times as many layers. With the
    // defaults, operands that span the frame stay in one tile. A new layer
    // texture costs its bytes in memory and, on a software rasterizer
    // (llvmpipe), a first frame the time to zero them (144 MiB: about
    // 75 ms); more tiles cost every frame a few more passes, and on a GPU
    // a wait for each. A program that draws one frame (strata-render) gains
    // by cutting sooner: it never reuses the texture. Unset: the device's
    // (Renderer::deviceSettings): 64 MiB on a software rasterizer, none
    // (the budget) on a GPU; coverageTiling() where no device has said.
    std::optional<std::size_t> coverageTilingFrom;
    double coverageTilingDraws = 2.0;
    bool keepPeelLayers = false;               // copy every operand's peeled layers into Frame::peelLayers (debug views)
    bool keepBlockForms = false;               // record each pixel's evaluator form in Frame::blockForms (figures, tests)
    // Evaluate every pixel with the general (array) form of the evaluator,
    // not the fastest form that holds its block: slower, the same image
    // (tests compare the forms).
    bool generalEvaluator = false;
    // Specialise each evaluator block's tree to the operands whose screen
    // hull (the convex hull of a leaf's projected vertices) reaches it, not
    // only its screen rectangle: fewer operands per block where thin solids
    // lie aslant. false: rectangles alone. The same image either way (tests
    // compare them).
    bool screenHulls = true;
    // Mark each pixel's leaf in the stencil where the driver can
    // (ARB_shader_stencil_export), so the normal pass skips other leaves'
    // pixels early; false: one mark for all (tests compare the two).
    bool leafMarks = true;
    // Peel a non-convex operand of at least this many triangles in one
    // geometry pass, through per-pixel lists of its fragments, where no pixel
    // holds more than 8 of them; smaller ones a dual-peel pass per layer,
    // which costs them less than the lists' clears, resolve and read-back.
    // 0: every non-convex operand; -1: none. The layers are the same either
    // way (tests compare them).
    int fragmentListTriangles = 4096;
    // Peel as one operand (ConvexGroups.h): the convex operands that one
    // intersection joins, and, where every ray starts outside the scene,
    // the operands that only unions lead to, up to 65,535 a group. Each
    // group is one layer holding its interval, drawn in one multi-draw, and
    // one operand for the evaluator where there were many. false: each its
    // own operand. The images are the same either way (tests compare them).
    // Frames with keepPeelLayers, and the result peel, group no unions; the
    // first never groups.
    bool groupOperands = true;
    // An intersection is grouped only where it joins at least this many
    // convex operands (at least 2). Fewer stay operands of their own: the
    // evaluator's register form holds up to eight operands in registers,
    // and a group's passes (four over its members, a clear and a resolve)
    // cost more than their one-pass layers in the convex batch. On
    // llvmpipe at 1024 x 768 strata-bench's intersection of 8 spheres drew
    // in 22 ms apart and 35 ms grouped, that of 9 in 34 ms apart and 22 ms
    // grouped.
    int convexGroupFrom = 9;
    // Unions are grouped only where at least this many operands are ones
    // that only unions lead to. A group's passes (four over its members, and
    // clears, a copy and a resolve over its rectangle) cost more than the
    // one-pass layers of a few operands: on an H200, models of 22 to 46
    // leaves drew 0.3 to 0.7 ms slower as union groups, while 1535 drew in
    // 1.9 ms instead of 9.0.
    int unionGroupFrom = 64;
    // Draw a frame whose tree is a union of leaves, seen from outside, as
    // depth-tested geometry straight into the shading inputs: no peel, no
    // evaluator, no normal pass (engine/render/PlainPass.h; docs/algorithm.md,
    // "Plain frames"). false: such frames run every pass, as any tree does
    // (tests compare the two).
    bool plainUnions = true;
    // Where the root is a union of plain leaves and of CSG, the plain
    // leaves are drawn plainly before the rest is evaluated (in the frames
    // a plain frame would take, with plainUnions) when they reach at least
    // this share of the blocks the frame draws where no CSG operand does
    // (render::plainBesideShare; 0: always, above 1: never). On fewer, the
    // plain pass's own targets and the evaluator's reading of them cost
    // about what they save: on llvmpipe, OpenSCAD's examples where they
    // reach 30 to 37 % of the blocks alone took 1.0 to 1.15 times as long
    // drawn so, those from 50 % 0.57 to 0.97 times.
    double plainBesideFrom = 0.4;
    // Wait for the GPU after each pass (glFinish), so that FrameStats' pass
    // figures are the GPU's time. false: the frame waits only where it
    // needs to (the evaluator's faces, read back for the normal pass) and
    // at its end, so that on a GPU the CPU issues the next pass while the
    // last one runs; each pass's figure is then the CPU's time to issue it,
    // and totalMs the frame's true cost. Each wait costs a GPU about 0.1 ms.
    bool passTimes = true;
    // What render() reads back beside the image and the leaves: leave out
    // what the caller will not use (Frame::depth, Frame::normal stay empty),
    // and its read-back with it (20 bytes a pixel).
    bool readDepth = true;
    bool readNormal = true;

    static constexpr std::size_t kMemoryBudget = std::size_t(512) << 20;
    static constexpr std::size_t kSoftwareCoverageTilingFrom = std::size_t(64) << 20;
    std::size_t budget() const { return memoryBudget.value_or(kMemoryBudget); }
    std::size_t coverageTiling() const { return coverageTilingFrom.value_or(kSoftwareCoverageTilingFrom); }
};

struct FrameStats {
    // Wall clock of each pass, every tile, a glFinish (or a read-back) after
    // each where RenderSettings::passTimes asks:
    // peel, evaluate (the CSG evaluator), normal (the normal pass), plain
    // (a plain frame's draws, in place of those three, or those of the
    // plain leaves beside the CSG), shade (shading and
    // translucent leaves), readback (render() only).
    double peelMs = 0, evaluateMs = 0, normalMs = 0, plainMs = 0, shadeMs = 0, readbackMs = 0, totalMs = 0;
    // The frame was drawn plainly (RenderSettings::plainUnions): its leaves
    // drawn depth-tested, `tiedLeaves` of them a second time for ties:
    // `tiedTriangles` of their triangles, those that come near another
    // leaf's (0: every triangle of those leaves).
    bool plain = false;
    std::size_t tiedLeaves = 0, tiedTriangles = 0;
    // Leaves drawn plainly beside the CSG (the root a union of them and of
    // more), before the rest was peeled and evaluated: 0 where none was.
    // Their draws' time is plainMs.
    std::size_t plainBesideLeaves = 0;
    // The surfaces were lit as they were drawn (no outline: by the plain
    // pass, or by the normal pass where no normal is read back), and no
    // shade pass ran.
    bool litAsDrawn = false;
    // Peel passes used, per tree leaf: 0 for leaves not drawn, among them a
    // leaf identical to a lower one, which shares that one's layers
    // (IdenticalLeaves.h).
    std::vector<int> layersPerLeaf;
    std::size_t textureBytes = 0;              // layered-texture memory in use
    int textureAllocations = 0;                // layered textures (re)created during the frame
    int operands = 0;                          // leaves in the CSG product
    std::size_t coveredPixels = 0;             // pixels where the result has a surface
    std::size_t unresolvedPixels = 0;          // pixels the evaluator could not finish (llvmpipe's loop limit); drawn empty
    int tiles = 1;                             // screen tiles / operand batches used to stay in budget
    int peelPasses = 0;                        // geometry passes of the peel: one per operand and layer, every tile
    int listPeeledOperands = 0;                // operands peeled in one pass through fragment lists, every tile
    // 16x16 blocks the evaluator drew in each of its forms (EvaluatePass.h);
    // blocks whose result is constant are not drawn.
    std::size_t firstSurfaceBlocks = 0, registerBlocks = 0, productBlocks = 0, arrayBlocks = 0;
    std::vector<std::string> notes;            // what the renderer decided (tiling, clamping, ...)
};

// One dual-peel layer of one operand (RenderSettings::keepPeelLayers), as the
// original paper's figures show them. Row 0 is the TOP row. Depths are view
// depths dot(P - eye, f); +inf where the layer caught nothing. Where the layer
// caught a single surface, nearDepth == farDepth.
struct PeelLayerImage {
    int leaf = -1;                  // tree leaf index of the operand
    int layer = 0;                  // 0: the outermost pair (nearest and farthest surfaces)
    std::vector<float> nearDepth;   // W*H: the layer's nearest surface
    std::vector<float> farDepth;    // W*H: the layer's farthest surface
};

// The form of the evaluator a 16x16 block of pixels was drawn with
// (docs/algorithm.md, "Per 16x16 block"); None: the result is constant there
// and the block was not drawn.
enum class BlockForm : std::uint8_t { None, FirstSurface, Register, Product, Array };

// One rendered frame, read back. Row 0 is the TOP row (as in image files).
struct Frame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;   // W*H*4, shaded image
    std::vector<float> depth;         // W*H, view depth dot(P - eye, f); +inf on miss (empty: !readDepth)
    std::vector<glm::vec3> normal;    // W*H, world-space unit outward normal of the result; 0 on miss (empty: !readNormal)
    std::vector<std::int32_t> leaf;   // W*H, tree leaf index of the visible surface; -1 on miss
    std::vector<PeelLayerImage> peelLayers;  // with RenderSettings::keepPeelLayers: by operand, then layer
    std::vector<BlockForm> blockForms;       // with RenderSettings::keepBlockForms: W*H, each pixel's block's form
    FrameStats stats;
};

// One round of Renderer::sampleResult over one tile: the round-th place,
// counted from 0, where each pixel's ray changes between outside and inside
// the result.
struct ResultRound {
    int round = 0;
    int x = 0, y = 0, width = 0, height = 0;  // the tile in frame pixels: column x from the left, row y from the top
    std::span<const float> depth;             // tile pixels, rows top first: view depth; +inf where the ray has no such change
    std::span<const glm::vec3> normal;        // world-space unit outward normal of the result there
    std::size_t unresolved = 0;               // pixels the evaluator could not finish (llvmpipe's loop limit)
};

}  // namespace strata::render
