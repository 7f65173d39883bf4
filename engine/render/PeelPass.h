#pragma once
// The peel pass: each operand's surfaces on every pixel of a tile, as dual
// depth-peeled layers (Bavoil & Myers 2008) in one RG32F array texture.
//
// Layer l of an operand holds (-near_l, far_l): its l-th nearest and l-th
// farthest tagged depths (shaders/csg/surface.glsl), or (-FLT_MAX, -FLT_MAX)
// where nothing was left to peel. Each layer costs one geometry pass over the
// operand with MAX blending; the next pass reads the previous layer and keeps
// only what lies strictly between. Layers of all operands sit one after the
// other in the texture; the texture is sized to the tile and grows as `auto`
// peeling finds deeper operands, within the memory budget.
//
// Auto peeling stops once a pass would find nothing: the first pass of a
// non-convex operand counts each pixel's surfaces into a stencil texture
// (INCR), and before pass l an occlusion query over a fullscreen triangle,
// stencil-tested "count > 2l", asks whether any pixel has surfaces left. The
// final, empty geometry pass of plain query-after-draw peeling becomes a
// rectangle of stencil reads. Passes l >= 1 test the same stencil too, so
// pixels already peeled to the end are dropped before the shader runs.
//
// A non-convex operand of many triangles is first peeled in one geometry
// pass instead (`PeelRequest::listTriangles`): each fragment appends its tagged depth to its
// pixel's list of up to kCollectCapacity (an atomic count and an array image,
// a k-buffer), and a fullscreen pass over the operand's rectangle derives
// every layer from the list by the same rule as the passes above (layer l
// keeps what lies strictly between layer l-1's near and far), writing them
// with image stores. Where a pixel holds more fragments than that, the lists
// are dropped and the operand is peeled pass by pass as above. The layers are
// the same either way, bit for bit (tests compare them).
//
// A group (ConvexGroups.h: an intersection of convex operands, or a union
// of operands of which only the first layer matters) is one operand of one
// layer, the one a convex operand with the group's interval would have,
// peeled first by GroupPeel (two depth-tested passes over its members and a
// resolve), which also keeps which member makes each surface.
//
// Convex operands need one pass each and no previous layer: where the driver
// can route a draw to a layer from the vertex stage (ARB_shader_draw_parameters
// and ARB_shader_viewport_layer_array), they are all peeled by one multi-draw
// into the layered texture, instead of one framebuffer change and draw each.
//
// GL state: draws into its own framebuffer with viewport (-tile.x, -tile.y, W,
// H), so the tile's pixels land at the texture's origin with the frame's exact
// pixel centres; enables blending (MAX), the scissor test and (for auto
// peeling's counts, in its own stencil texture) the stencil test while it
// runs, sets the stencil function, and disables all three before returning.
// Depth test and face culling must be off.

#include <cstddef>
#include <span>
#include <vector>

#include "GroupPeel.h"
#include "SceneBuffers.h"
#include "ShaderInterface.h"
#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Query.h"
#include "strata/gpu/Texture.h"

namespace strata::render {

struct OperandLayers {
    int first = 0;  // first layer in PeelPass::layers()
    int count = 0;  // layers peeled; 0 when the operand misses the tile
    int idsLayer = -1;  // a group's layer of groupIds() (its index among the tile's groups); -1 for the rest
};

struct PeelRequest {
    int fixedLayers = 0;              // > 0: that many passes per non-convex operand; 0: auto
    std::size_t budgetBytes = 0;      // most bytes the layer texture may take
    // Per operand (empty: none): its first layer is all the result can
    // show of it, so it is peeled once like a convex operand (see
    // Renderer.cpp: operands that only unions lead to, every ray starting
    // outside).
    std::span<const char> firstLayerOnly;
    // Peel non-convex operands of at least this many triangles in one pass
    // through per-pixel fragment lists where they fit (see above); < 0: none.
    int listTriangles = 0;
    // Per operand (empty: none): the member leaves of a group, else empty.
    std::span<const std::vector<int>> groups;
    // Per operand (empty: none): 1 where its group is a union (csg::CompiledTree::unionGroups).
    std::span<const char> unionGroups;
    // The most members a group may have: an intersection's count must fit
    // the stencil, a union's numbers the ids.
    static constexpr std::size_t kMostGroupMembers = GroupPeel::kMostMembers;
    static constexpr std::size_t kMostUnionMembers = GroupPeel::kMostUnionMembers;
};

class PeelPass {
public:
    PeelPass();  // compiles the shaders; needs a current context

    // Peels `operandLeaves` (tree leaf indices) over `tile`, skipping operands
    // whose screen rectangle misses the tile. Fills `out`, one
    // entry per operand. Returns false, having drawn nothing useful, when the
    // layers do not fit the budget (or the GPU's array-layer limit) at this
    // tile size: the caller splits the tile and tries again.
    // Each operand's layers are cleared and drawn only inside its screen
    // rectangle `rects[k]`, widened to the evaluator's 16x16 blocks (`block`
    // pixels, counted from the tile's corner): texels outside it are never read.
    bool run(const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
             std::span<const int> operandLeaves, std::span<const PixelRect> rects, int block,
             const PeelRequest& request, std::vector<OperandLayers>& out);

    static constexpr std::size_t kBytesPerTexel = 8;  // one RG32F texel of a layer
    // Fragments a pixel's list holds when collecting: up to 4 layers.
    static constexpr int kCollectCapacity = shader::kCollectCapacity;
    static_assert(kCollectCapacity == 8, "shaders/csg/resolve.frag reads a list as two vec4s");
    // The lists' images (kCollectCapacity R32F layers and an R32UI count) per
    // pixel, counted in the estimate where they are needed.
    static constexpr std::size_t kCollectScratchBytes = kCollectCapacity * 4 + 4;

    // What a tile's operands would need if the fixed count holds, or a first
    // guess for auto (1 layer per convex or first-layer-only operand, 2 per
    // other, 1 scratch): the layer texture's layers, and the images of their
    // own that groups and fragment lists take beside it.
    struct LayerEstimate {
        int layers = 1;
        std::size_t scratchBytesPerPixel = 0;
        std::size_t bytesPerPixel() const {
            return static_cast<std::size_t>(layers) * kBytesPerTexel + scratchBytesPerPixel;
        }
    };
    static LayerEstimate estimateLayers(const SceneBuffers& scene, std::span<const int> operandLeaves,
                                        std::span<const char> inTile, const PeelRequest& request);

    // Where operand layers are valid: `rect` (frame pixels) widened to whole
    // `block`s counted from the tile's corner, clipped to the tile, in texture
    // pixels (relative to the tile). Texels outside it hold stale data.
    static PixelRect region(const PixelRect& rect, const PixelRect& tile, int block);

    const gpu::Texture& layers() const { return layers_; }
    // The groups of the last run(): which member makes each surface
    // (GroupPeel::ids), a layer per group (OperandLayers::idsLayer).
    const gpu::Texture& groupIds() const { return group_.ids(); }
    // The layers and, once an operand was collected, the fragment lists.
    std::size_t textureBytes() const {
        return (layers_.id() ? layers_.byteSize() : 0) + (fragments_.id() ? fragments_.byteSize() : 0) +
               (fragmentCounts_.id() ? fragmentCounts_.byteSize() : 0) + group_.bytes();
    }
    int maxArrayLayers() const { return maxArrayLayers_; }
    int passes() const { return passes_; }  // geometry passes in the last run()
    int collected() const { return collected_; }  // operands peeled through fragment lists in the last run()
    int allocations() const { return allocations_; }  // layer textures created in the last run()

private:
    // What one run() peels, as its strategies below need it.
    struct Job {
        const SceneBuffers& scene;
        const PixelRect& tile;
        std::span<const int> operandLeaves;
        std::span<const PixelRect> rects;
        int block;
        const PeelRequest& request;
        std::span<const char> inTile;  // per operand: its rectangle meets the tile
        std::size_t layerBudget;       // the budget less the groups' and lists' images
        PixelRect valid(std::size_t k) const { return region(rects[k], tile, block); }
    };
    // What a strategy returns in place of a layer count: the layers would
    // not fit the budget, or a pixel's fragments overflowed its list.
    static constexpr int kOverBudget = -1;
    static constexpr int kListsOverflowed = -2;

    // Makes room for `needed` layers of a tile of `width` x `height`, keeping
    // the first `keep` layers. False when that exceeds the budget.
    bool reserve(int width, int height, int needed, int keep, std::size_t budgetBytes);
    // Sets `count` layers from `first` to (-FLT_MAX, -FLT_MAX), "nothing
    // here", inside `valid` (texture pixels).
    void clearLayers(const PixelRect& valid, int first, int count);
    // The GL state of run()'s passes, and back.
    void beginPasses(const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile);
    void endPasses();

    // The strategies, in the order run() applies them. Each gives its
    // operands layers from `used` (or `first`) on; the first two return the
    // layers used after them, the others the operand's layer count (or
    // kOverBudget).
    // Groups of convex operands, a layer each, through GroupPeel.
    int peelGroups(const Job& job, const ViewSetup& view, std::vector<OperandLayers>& out);
    // The one-pass operands not yet peeled, a layer each, in one multi-draw.
    int peelConvexBatch(const Job& job, std::vector<OperandLayers>& out, int used);
    // Operand k by the first strategy below that applies to it.
    int peelOperand(const Job& job, std::size_t k, int first);
    // `passes` passes of dual depth peeling (1 for a one-pass operand).
    int peelFixed(const Job& job, int leaf, int first, int passes);
    // Passes until no pixel has surfaces left (auto peeling, see above).
    int peelAuto(const Job& job, int leaf, int first);
    // One pass, `pass` of the operand `leaf`, into layer `layer`; `automatic`:
    // with auto peeling's stencil counts and query.
    void peelPass(const SceneBuffers& scene, int leaf, int layer, int pass, bool automatic);
    // One geometry pass into per-pixel fragment lists, then the lists to
    // layers (auto: up to kCollectCapacity / 2). kListsOverflowed where a
    // pixel's fragments overflowed its list (nothing useful drawn).
    int peelThroughLists(const Job& job, int leaf, const PixelRect& valid, int first);

    gpu::Program first_;  // PEEL_FIRST: everything passes
    gpu::Program next_;   // reads the previous layer
    gpu::Program batch_;  // PEEL_FIRST and LAYERED: convex operands in one multi-draw
    bool batched_ = false;  // the driver has what batch_ needs
    gpu::Buffer commands_;  // DrawElementsIndirectCommand per operand of the batch
    gpu::Buffer drawLayers_;
    // Whether a pixel of the operand being peeled has more than `surfaces`
    // surfaces, by the counts of its first pass (see above). True where the
    // 8-bit counts cannot tell (surfaces >= 255).
    bool anyDeeperThan(int surfaces);

    gpu::Framebuffer target_;  // layered, for the convex batch
    gpu::Framebuffer counted_;  // one layer and the counts: the other passes
    gpu::Texture layers_;
    gpu::Texture counts_;  // STENCIL_INDEX8 per pixel of a tile: surfaces of the operand being peeled
    gpu::Program deeper_;  // fullscreen, stencil-tested, no output
    gpu::Query drawn_;         // did the last pass draw anything?
    gpu::Query deeperDrawn_;   // did deeper_ pass anywhere?
    gpu::Program collect_;  // COLLECT: appends each fragment to its pixel's list
    gpu::Program resolve_;  // fullscreen: lists to layers
    GroupPeel group_;
    gpu::Framebuffer listTarget_;  // no attachments, the tile's size: collect_ and resolve_ write images only
    gpu::Texture fragments_;       // R32F, kCollectCapacity layers: each pixel's list
    gpu::Texture fragmentCounts_;  // R32UI: fragments appended per pixel
    gpu::Buffer resolveStats_;     // uint most layers, uint most fragments (resolve.frag)
    int maxArrayLayers_ = 256;
    int passes_ = 0;
    int collected_ = 0;
    int allocations_ = 0;
};

}  // namespace strata::render
