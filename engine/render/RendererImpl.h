#pragma once
// The renderer's state and its members, for the render room's own files:
// Renderer.cpp (the facade, a scene's upload, a frame planned and carried
// out, read-back), TileRunner.cpp (the tiles of a frame: their plan, and
// the peel, evaluate and normal passes run over each) and ResultSampler.cpp
// (sampleResult: the result peeled round by round).

#include "strata/render/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "AlphaPass.h"
#include "EvaluatePass.h"
#include "FramePlan.h"
#include "FrameTargets.h"
#include "GroupPeel.h"
#include "NormalPass.h"
#include "PeelPass.h"
#include "PlainPass.h"
#include "SceneBuffers.h"
#include "ShadePass.h"
#include "ShaderInterface.h"
#include "TranslucentPass.h"
#include "ViewSetup.h"
#include "strata/core/Error.h"
#include "strata/core/Timing.h"
#include "strata/csg/CompiledTree.h"
#include "strata/csg/ConvexGroups.h"
#include "strata/csg/IdenticalLeaves.h"
#include "strata/gpu/Check.h"
#include "strata/render/ColorScheme.h"

namespace strata::render {

using Clock = std::chrono::steady_clock;

// Flips the row order in place: GL's bottom-up rows into image rows, top
// first, and back.
template <class T>
inline void flipRows(std::span<T> rows, int width, int height, int channels) {
    const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
    for (int y = 0; y < height / 2; ++y) {
        const auto top = rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y));
        const auto bottom = rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(height - 1 - y));
        std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(row), bottom);
    }
}

// The fixed-function state every pass of a frame starts from.
void resetDrawState();

// A pass made on its first use: each compiles its shaders when made, and a
// frame that never needs one (a plain frame needs no peel, evaluator or
// normal pass; most models have no translucent leaf) should not pay for
// them, least of all the first frame of a process.
template <class Pass>
class Lazy {
public:
    Pass* operator->() {
        if (!pass_) pass_.emplace();
        return &*pass_;
    }

private:
    std::optional<Pass> pass_;
};

struct Renderer::Impl {
    Lazy<PeelPass> peel;
    Lazy<EvaluatePass> evaluate;
    Lazy<NormalPass> normals;
    Lazy<PlainPass> plain;
    Lazy<ShadePass> shade;
    Lazy<AlphaPass> alpha;
    Lazy<TranslucentPass> translucent;
    // The leaves a plain frame of the scene draws (PlainPass::plainLeaves;
    // none: the scene is not drawn plainly), and whether the plain pass
    // still has another scene's.
    std::vector<int> plainLeaves;
    bool plainStale = true;
    // The frame's RenderSettings::passTimes: passDone() waits for the GPU.
    bool passTimes = true;
    void passDone() const {
        if (passTimes) glFinish();
    }
    // Where the root is a union of plain leaves (solids with volume that
    // only unions lead to) and of more: those leaves, which such a frame
    // draws plainly before the rest is evaluated (PlainPass::Output::beside),
    // and the tree without them (leaves empty), its operands their own and
    // grouped. None where plainLeaves holds the whole scene.
    std::vector<int> besideLeaves;
    FrameTargets targets;
    SceneBuffers scene;
    // The tree compiled with every operand its own (`separate`), with
    // convex intersections grouped (ConvexGroups.h), and with those and the
    // operands that only unions lead to grouped (for views where every ray
    // starts outside), each with its reachedByUnionsOnly; `current` is the
    // one the evaluator holds.
    struct Compilation {
        csg::CompiledTree tree;
        std::vector<char> unionsOnly;
    };
    Compilation separate, grouped, unionGrouped, besideSeparate, besideGrouped;
    std::vector<char> besideConvexOperands;  // convexOperands of besideSeparate
    std::size_t unionOnlyOperands = 0;  // the operands groupUnionOperands may join (RenderSettings::unionGroupFrom)
    // Which of separate's operands are convex, and the
    // RenderSettings::convexGroupFrom that grouped and unionGrouped were made
    // with (-1: none yet). groupTrees makes them again for another: a frame
    // whose setting differs calls it before it plans.
    std::vector<char> convexOperands;
    int groupedFrom = -1;
    void groupTrees(int convexGroupFrom);
    const Compilation* current = nullptr;
    const Compilation& compilation(TreeForm form) const {
        switch (form) {
            case TreeForm::Separate: return separate;
            case TreeForm::Grouped: return grouped;
            case TreeForm::UnionGrouped: return unionGrouped;
            case TreeForm::BesidePlainSeparate: return besideSeparate;
            default: return besideGrouped;
        }
    }
    std::vector<TranslucentLeaf> translucentLeaves;
    std::vector<AlphaLeaf> alphaLeaves;
    std::size_t leafCount = 0;
    std::size_t copiedLeaves = 0;  // leaves identical to a lower one (IdenticalLeaves.h)
    bool hasScene = false;
    GLint maxTextureSize = 0;
    // sampleResult's: where each tile's rounds go (null in other frames),
    // and each pixel's last change found (EvaluatePass::runResultRound).
    const std::function<void(const ResultRound&)>* roundSink = nullptr;
    gpu::Texture resultStart;
    bool canMarkLeaves = FrameTargets::canMarkLeaves();

    // The device: a software rasterizer (llvmpipe), and the GPU's own
    // memory in bytes where its driver says (0: unknown).
    bool softwareRasterizer = false;
    std::size_t deviceMemory = 0;
    Impl();
    RenderSettings deviceSettings(const RenderSettings& settings) const;

    // Renderer::setScene's; `release` (`model` itself, or null): let the
    // meshes go as they reach the GPU.
    void setScene(const scene::Tree& tree, const model::Model& model, model::Model* release);

    // A plain frame (PlainPass.h) in place of the peel, evaluate and normal passes.
    // `drawn` holds every pixel its leaves cover.
    // `litAs`: also light it as drawn, into the cleared image (no outline).
    void drawPlain(const ViewSetup& view, const PixelRect& drawn, const std::vector<glm::vec2>& baseColors,
                   const PlainPass::Output& output, Frame& frame);
    // The leaves the plain pass draws: plainLeaves, or besideLeaves.
    const std::vector<int>& plainPassLeaves() const { return plainLeaves.empty() ? besideLeaves : plainLeaves; }
    // Every pass; the images stay on the GPU. Fills frame's size and stats.
    // `aovs`: the depth, normal and leaf images will be read back.
    ViewSetup drawFrame(const camera::Camera& camera, const RenderSettings& settings, Frame& frame, bool aovs);
    // The frame's view; throws strata::Error before setScene, for a negative
    // layer count, or for an image larger than the GPU's largest texture.
    ViewSetup frameView(const camera::Camera& camera, const RenderSettings& settings) const;
    // Each leaf's screen rectangle in one frame's view (screenRect of its
    // vertices), and its screen hull where the frame wants hulls (at most
    // `mostHullVertices` vertices, else none), worked out together at the
    // leaf's first use: the plan, the operands' rectangles and the
    // evaluator's blocks ask for the same leaves.
    class LeafRects {
    public:
        LeafRects(const ViewSetup& view, const SceneBuffers& scene, std::size_t mostHullVertices)
            : view_(view), scene_(scene), mostHullVertices_(mostHullVertices), bounds_(scene.leaves().size()),
              known_(scene.leaves().size(), 0) {}
        const PixelRect& operator()(int leaf) { return of(leaf).rect; }
        const ScreenHull& hull(int leaf) { return of(leaf).hull; }
        const ViewSetup& view() const { return view_; }

    private:
        const ScreenBounds& of(int leaf) {
            const auto i = static_cast<std::size_t>(leaf);
            if (!known_[i]) {
                bounds_[i] = screenBounds(view_, scene_.leafVertices(leaf), mostHullVertices_);
                known_[i] = 1;
            }
            return bounds_[i];
        }
        const ViewSetup& view_;
        const SceneBuffers& scene_;
        std::size_t mostHullVertices_;
        std::vector<ScreenBounds> bounds_;
        std::vector<char> known_;
    };
    // Where a frame's operands lie on screen (drawFrame's, for peelAndEvaluate).
    struct ScreenRects {
        std::vector<PixelRect> rects;      // each operand's screen rectangle
        std::vector<int> markLeaves;       // the leaves that hold mark slots
        std::vector<PixelRect> markRects;  // and their screen rectangles
        PixelRect drawn;                   // every pixel the frame draws: all of the above
    };
    ScreenRects screenRects(const csg::CompiledTree& compiled, const FramePlan& plan, LeafRects& leafRects) const;
    // besideLeaves and the trees without them, from the scene's tree and
    // compileTree's arguments (setScene's, after separate and plainLeaves).
    void besidePlain(const scene::Tree& tree, const std::vector<bool>& empty, const std::vector<int>& same);
    // The frame's plan (FramePlan.h) from what this renderer knows of its scene.
    FramePlan planFrame(const ViewSetup& view, const RenderSettings& settings, bool aovs, LeafRects& leafRects) const;
    // `plan`: the frame's (planFrame).
    // `rects`: each operand's screen rectangle (screenRect of its vertices).
    // `markLeaves`, `markRects`: the leaves that hold mark slots (operands,
    // and a group's members in its place) and their screen rectangles.
    // `baseColors`: ShadePass::baseColors for this frame's colour scheme.
    // `litAs`: the normal pass lights the surfaces into the image, which
    // the caller has cleared to the background (NormalPass.h).
    void peelAndEvaluate(const ViewSetup& view, const FramePlan& plan, const std::vector<PixelRect>& rects,
                         const std::vector<int>& markLeaves,
                         const std::vector<PixelRect>& markRects, const RenderSettings& settings,
                         const std::vector<glm::vec2>& baseColors, const std::optional<Lighting>& litAs,
                         LeafRects& leafRects, Frame& frame);
    // What every tile of a frame reads (peelAndEvaluate's arguments).
    struct TileInputs {
        const ViewSetup& view;
        const FramePlan& plan;
        const std::vector<PixelRect>& rects;
        const std::vector<ScreenHull>& hulls;
        const std::vector<int>& markLeaves;
        const std::vector<PixelRect>& markRects;
        const RenderSettings& settings;
        const std::vector<glm::vec2>& baseColors;
        const PeelRequest& request;
        const std::optional<Lighting>& litAs;
    };
    struct TileCounts {
        int drawn = 0;   // tiles peeled, evaluated and given normals
        int splits = 0;  // tiles split in four because their layers outgrew the budget
    };
    // The tile grid the frame starts from (planTileGrid, FramePlan.h), with
    // PeelPass's estimates of each tile's layers.
    TileGrid planTiles(const TileInputs& in) const;
    // Peels each tile of `grid`, then evaluates it and recovers its normals;
    // a tile whose auto peeling outgrows the budget is split in four.
    TileCounts runTiles(const TileInputs& in, const std::vector<PixelRect>& grid, Frame& frame);
    // The result peel's rounds over one peeled tile (sampleResult).
    void peelResultRounds(const TileInputs& in, const PixelRect& tile, const std::vector<OperandLayers>& layers,
                          Frame& frame);
    // The evaluate and normal passes over one peeled tile.
    void evaluateTile(const TileInputs& in, const PixelRect& tile, const std::vector<OperandLayers>& layers,
                      Frame& frame);
    // Paints the tile's blocks' forms (EvaluatePass::run) into frame.blockForms.
    void keepBlockForms(const PixelRect& tile, const std::vector<BlockForm>& forms, Frame& frame);
    void keepLayers(const PixelRect& tile, const std::vector<int>& operands, const std::vector<PixelRect>& rects,
                    const std::vector<OperandLayers>& layers, Frame& frame);
    // Shade, alpha and translucent passes over the G-buffer in `targets`.
    // `marked`: ShadePass::run's. `lit`: the image is lit already (a frame
    // lit as drawn), only the alpha and translucent passes are left.
    // `windowDepth`: TranslucentPass::run's, for a plain frame only shown.
    void shadeFrame(const ViewSetup& view, const ColorScheme& scheme, const RenderSettings& settings,
                    const std::optional<PixelRect>& marked, bool lit = false,
                    const gpu::Texture* windowDepth = nullptr);
    void readColor(Frame& frame);  // the shaded image into frame.rgba, rows top first
    void readBack(Frame& frame, const RenderSettings& settings);  // what settings.read* ask, beside image and leaves
};

}  // namespace strata::render
