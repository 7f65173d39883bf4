#pragma once
// What a frame does, decided on the CPU from the scene, the view and the
// settings before any pass runs: which of the scene's compiled trees the
// evaluator walks, whether the frame is drawn plainly (PlainPass.h),
// peeled and evaluated, or neither, and how its surfaces are lit. No GL:
// Renderer.cpp carries the plan out.

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "ViewSetup.h"
#include "strata/csg/CompiledTree.h"
#include "strata/render/Frame.h"

namespace strata::render {

// The scene's tree compiled five ways (Renderer::setScene): every operand
// its own; convex intersections grouped (ConvexGroups.h); and those with
// the operands that only unions lead to grouped, for views where every ray
// starts outside; and where the root is a union of plain leaves and of
// more (PlainPass.h, Output::beside), the tree without those leaves, its
// operands their own or grouped, for the frames that draw them plainly.
enum class TreeForm { Separate, Grouped, UnionGrouped, BesidePlainSeparate, BesidePlainGrouped };
inline constexpr std::size_t kTreeForms = 5;

// What the renderer knows of the scene and the view when it plans a frame.
struct FrameFacts {
    bool outside = false;               // every ray starts outside the model (beyondNearPlane)
    bool plainScene = false;            // a union of leaves a plain frame can draw (PlainPass::plainLeaves)
    bool plainBesideScene = false;      // a union of such leaves and of more (Renderer's besidePlain)
    double plainBesideShare = 0.0;      // of the frame's blocks, those only such leaves reach (plainBesideShare;
                                        // RenderSettings::plainBesideFrom)
    bool resultPeel = false;            // Renderer::sampleResult's frame: it walks past the first surface
    bool aovs = false;                  // the depth, normal and leaf images will be read back
    std::size_t unionOnlyOperands = 0;  // the operands groupUnionOperands may join
    std::array<csg::CompiledTree::Kind, kTreeForms> kinds{};  // each TreeForm's kind: an empty result, everything, or code
};

struct FramePlan {
    TreeForm form = TreeForm::Separate;  // the tree the evaluator walks
    bool plainFrame = false;             // drawn plainly: no peel or evaluator
    bool plainBeside = false;            // the plain leaves drawn plainly, the rest peeled and evaluated after
    bool shownOnly = false;              // a plain frame nothing reads back
    bool evaluated = false;              // peeled and evaluated
    bool aovNormals = false;             // its normals are read back
    bool litAsDrawn = false;             // lit as its surfaces are drawn: no shade pass
    bool resultPeel = false;             // sampleResult's rounds: nothing shaded, a wider coincidence
    bool firstLayerOnly = false;         // every ray starts outside: the operands only unions lead to need one layer
};

FramePlan planFrame(const FrameFacts& facts, const RenderSettings& settings);

// Of the blocks (squares of `block` pixels on the frame's grid) that any of
// `plain` or `csg` meets, the share that only `plain` meets: the evaluator
// has nothing to do there once the plain leaves are drawn plainly.
double plainBesideShare(int width, int height, int block, const std::vector<PixelRect>& plain,
                        const std::vector<PixelRect>& csg);

// The peel layers a tile needs for the operands it meets: how many, and
// their bytes a pixel (PeelPass::estimateLayers).
struct TileEstimate {
    int layers = 1;
    std::size_t bytesPerPixel = 0;
};

// The tiles an evaluated frame is drawn in.
struct TileGrid {
    std::vector<PixelRect> tiles;
    std::size_t budgetTiles = 1;      // tiles the budget alone asks
    std::size_t wholeLayerBytes = 0;  // the layers' estimate for the frame in one tile
};

// The whole frame, or an even grid of quarters, of quarters of those, ...,
// as fine as the densest tile needs for its operands' layers to fit
// settings.memoryBudget; then finer while the layers take more than
// settings.coverageTilingFrom and a step draws at most
// settings.coverageTilingDraws times as many layers (operands small on
// screen), no tile cut for coverage below 64 pixels a side. `rects`: each operand's screen rectangle; `estimate(inTile)`:
// the layers of a tile that meets the operands `inTile` marks. Throws
// strata::Error where even the smallest tile's layers exceed the budget.
// Tiles are cut on a grid of `block` pixels (quarters).
TileGrid planTileGrid(int width, int height, const std::vector<PixelRect>& rects, const RenderSettings& settings,
                      int block, const std::function<TileEstimate(const std::vector<char>& inTile)>& estimate);

// `tile` cut in four on a grid of `block` pixels: each side of at least two
// blocks is halved (rounded up to whole blocks), a shorter one is kept, so
// no tile is thinner than a block unless the frame is. Empty parts are left
// out; a tile that cannot be cut comes back alone.
std::vector<PixelRect> quarters(const PixelRect& tile, int block);

// Bytes as the frame's notes and messages give them: "144.0 MiB".
std::string mebibytes(std::size_t bytes);

}  // namespace strata::render
