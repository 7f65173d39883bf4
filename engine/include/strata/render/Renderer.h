#pragma once
// The image-space CSG renderer: peel every operand into layers, evaluate the
// tree per pixel, shade the first visible surface. Needs a current OpenGL 4.5
// core context (strata::gpu) on the calling thread for its whole life.
//
// The passes (engine/render/*Pass.h, shaders/csg/) and what each owns:
//   peel       PeelPass        dual depth peeling into an RG32F array texture
//   evaluate   EvaluatePass    the compiled tree (strata/csg/CompiledTree.h) per pixel
//   normal     NormalPass      the visible leaves redrawn for face normals
//   plain      PlainPass       in place of those three for a union seen from
//                              outside: its front faces depth-tested into the G-buffer
//   shade      ShadePass       colours, light, Sobel outline
//   translucent TranslucentPass '%' and '#' leaves over the image
// GL state on return: depth test, stencil test, culling, blending and scissor test off;
// the viewport, bound program, vertex array, textures, storage buffers and
// draw framebuffer are whatever the last pass used (renderInto: the host's).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/render/ColorScheme.h"
#include "strata/geometry/Model.h"
#include "strata/scene/Tree.h"

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
    // screen tiles (FrameStats::tiles, ::notes). Too small for a 16x16 tile: strata::Error.
    std::size_t memoryBudget = std::size_t(512) << 20;
    // Within the budget, layers of more bytes than this are drawn in tiles
    // where the operands are small on screen: quarters of the frame (then
    // quarters of those, down to 64 pixels a side) while a quarter's layers
    // hold only the operands that meet it and each step's tiles together
    // draw at most coverageTilingDraws times as many layers. With the
    // defaults, operands that span the frame stay in one tile. A new layer
    // texture costs its bytes in memory and, on llvmpipe, a first frame the
    // time to zero them (144 MiB: about 75 ms); more tiles cost every frame
    // a few more passes. A program that draws one frame (strata-render)
    // gains by cutting sooner: it never reuses the texture.
    std::size_t coverageTilingFrom = std::size_t(64) << 20;
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
    // What render() reads back beside the image and the leaves: leave out
    // what the caller will not use (Frame::depth, Frame::normal stay empty),
    // and its read-back with it (20 bytes a pixel).
    bool readDepth = true;
    bool readNormal = true;
};

struct FrameStats {
    // Wall clock of each pass, every tile, a glFinish (or a read-back) after each:
    // peel, evaluate (the CSG evaluator), normal (the normal pass), plain
    // (a plain frame's draws, in place of those three), shade (shading and
    // translucent leaves), readback (render() only).
    double peelMs = 0, evaluateMs = 0, normalMs = 0, plainMs = 0, shadeMs = 0, readbackMs = 0, totalMs = 0;
    // The frame was drawn plainly (RenderSettings::plainUnions): its leaves
    // drawn depth-tested, `tiedLeaves` of them a second time for ties:
    // `tiedTriangles` of their triangles, those that come near another
    // leaf's (0: every triangle of those leaves).
    bool plain = false;
    std::size_t tiedLeaves = 0, tiedTriangles = 0;
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

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads the leaf meshes and compiles the tree (the passes' shaders are
    // compiled by the first frame that needs them). Call again after an edit.
    void setScene(const scene::Tree& tree, const geometry::Model& model);
    // The same, letting each leaf's mesh go as soon as it is on the GPU and
    // handing the memory back: for a caller that needs the meshes no more
    // (a million cubes then peak about 400 MB lower). `model` is left empty.
    void setScene(const scene::Tree& tree, geometry::Model&& model);

    // Renders and reads everything back.
    Frame render(const Camera& camera, const RenderSettings& settings);

    // Renders without reading anything back, and copies the shaded image into
    // the host's `framebuffer` (a GL framebuffer name; 0 is the default one)
    // with its lower-left corner at (x, y) in that framebuffer's pixels: for a
    // window or a host's own render target. Returns the frame's figures
    // (readbackMs covers the copy; coveredPixels is not counted).
    // Leaves that framebuffer bound for drawing.
    FrameStats renderInto(unsigned framebuffer, int x, int y, const Camera& camera, const RenderSettings& settings);

    // Every place along each pixel's ray where the result's membership
    // changes, front to back, by peeling the result: each tile's operands are
    // peeled once (every layer), then each round evaluates the tree again,
    // walking on from the change the round before found, until no ray of the
    // tile has one more. `onRound` gets each tile's rounds in order; a ray
    // whose changes end in one round has +inf in the rounds after. The rays
    // start at the near plane: for every change to show, the camera should
    // see the whole model from outside it (the export's orthographic views).
    // Nothing is shaded. Returns the figures (coveredPixels: changes found).
    FrameStats sampleResult(const Camera& camera, const RenderSettings& settings,
                            const std::function<void(const ResultRound&)>& onRound);

    // Shades a result computed elsewhere (the CPU reference of strata-render
    // --reference) with the same shade and translucent passes as render(), and
    // reads it back like render(). Every span holds camera.width * camera.height
    // values, rows top first as in Frame; `cut` is 1 where the leaf acts as a
    // subtracted operand. The returned Frame carries these AOVs unchanged.
    struct ExternalResult {
        std::span<const float> depth;
        std::span<const glm::vec3> normal;
        std::span<const std::int32_t> leaf;
        std::span<const std::uint8_t> cut;
    };
    Frame shade(const Camera& camera, const RenderSettings& settings, const ExternalResult& result);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strata::render
