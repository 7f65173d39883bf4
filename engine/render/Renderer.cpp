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

namespace {

using Clock = std::chrono::steady_clock;

std::string mebibytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return text;
}

// Leaves to draw translucent: '#' leaves in the CSG, and every leaf of the
// '%' subtrees (or marked Background), with OpenSCAD's colours.
std::vector<TranslucentLeaf> translucentLeaves(const scene::Tree& tree, const SceneBuffers& scene) {
    std::vector<char> background(tree.leaves.size(), 0);
    std::vector<int> stack(tree.background.begin(), tree.background.end());
    std::vector<char> seen(tree.nodes.size(), 0);
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= tree.nodes.size() || seen[static_cast<std::size_t>(n)]) continue;
        seen[static_cast<std::size_t>(n)] = 1;
        const scene::Node& node = tree.nodes[static_cast<std::size_t>(n)];
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf >= 0 && static_cast<std::size_t>(node.leaf) < tree.leaves.size()) {
                background[static_cast<std::size_t>(node.leaf)] = 1;
            }
        }
        stack.insert(stack.end(), node.children.begin(), node.children.end());
    }
    std::vector<TranslucentLeaf> out;
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        if (scene.leaf(static_cast<int>(i)).indexCount == 0) continue;
        if (background[i] || leaf.display == scene::Display::Background) {
            glm::vec4 color = kBackgroundModifierColor;
            if (leaf.color) color = glm::vec4(glm::vec3(*leaf.color), kBackgroundModifierColor.a);
            out.push_back({static_cast<int>(i), color});
        } else if (leaf.display == scene::Display::Highlight) {
            out.push_back({static_cast<int>(i), kHighlightColor});
        }
    }
    return out;
}

// Leaves in the CSG whose color() is translucent (alpha below 1; an unset
// alpha is 1), and which of them are alone in their OpenSCAD product: only
// unions lead to them from the root, counting an intersection or difference
// of which only one child has triangles as a union of that child (OpenSCAD
// leaves a leaf without geometry out of a product).
std::vector<AlphaLeaf> alphaLeaves(const scene::Tree& tree, const SceneBuffers& scene) {
    std::vector<AlphaLeaf> out;
    if (tree.root < 0) return out;
    const std::size_t n = tree.nodes.size();
    auto inRange = [n](int node) { return node >= 0 && static_cast<std::size_t>(node) < n; };
    // Whether each node's subtree holds a leaf with triangles: children first,
    // on an explicit stack (trees can be deep).
    std::vector<char> solid(n, 0), state(n, 0);  // state: 0 new, 1 children pushed, 2 done
    std::vector<int> stack{tree.root};
    while (!stack.empty()) {
        const int v = stack.back();
        const auto i = static_cast<std::size_t>(v);
        const scene::Node& node = tree.nodes[i];
        if (state[i] == 0) {
            state[i] = 1;
            if (node.kind == scene::NodeKind::Leaf) continue;
            for (int c : node.children)
                if (inRange(c) && state[static_cast<std::size_t>(c)] == 0) stack.push_back(c);
            continue;
        }
        stack.pop_back();
        if (state[i] == 2) continue;
        state[i] = 2;
        if (node.kind == scene::NodeKind::Leaf) {
            solid[i] = node.leaf >= 0 && static_cast<std::size_t>(node.leaf) < tree.leaves.size() &&
                       scene.leaf(node.leaf).indexCount > 0;
        } else {
            for (int c : node.children) solid[i] = solid[i] || (inRange(c) && solid[static_cast<std::size_t>(c)]);
        }
    }
    // Down from the root: whether only unions lead there.
    std::vector<char> alone(tree.leaves.size(), 0), seen(n, 0);
    std::vector<char> reached(tree.leaves.size(), 0);
    std::vector<std::pair<int, bool>> walk{{tree.root, true}};
    while (!walk.empty()) {
        const auto [v, unionsOnly] = walk.back();
        walk.pop_back();
        const auto i = static_cast<std::size_t>(v);
        if (seen[i] & (unionsOnly ? 2 : 1)) continue;
        seen[i] |= unionsOnly ? 2 : 1;
        const scene::Node& node = tree.nodes[i];
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf < 0 || static_cast<std::size_t>(node.leaf) >= tree.leaves.size()) continue;
            reached[static_cast<std::size_t>(node.leaf)] = 1;
            alone[static_cast<std::size_t>(node.leaf)] |= unionsOnly ? 1 : 0;
            continue;
        }
        int solidChildren = 0;
        for (int c : node.children) solidChildren += inRange(c) && solid[static_cast<std::size_t>(c)] ? 1 : 0;
        const bool keeps = node.kind == scene::NodeKind::Union || solidChildren <= 1;
        for (int c : node.children)
            if (inRange(c)) walk.emplace_back(c, unionsOnly && keeps);
    }
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        if (!reached[i] || !leaf.color || scene.leaf(static_cast<int>(i)).indexCount == 0) continue;
        const glm::vec4 color(*leaf.color);
        if (color.a < 0.0f || color.a >= 1.0f) continue;
        out.push_back({static_cast<int>(i), color, alone[i] != 0});
    }
    return out;
}

// Per operand of `compiled`: whether only ORs lead from the result to its
// (not complemented) literal. The result is then true wherever the operand
// is: once a ray enters it, the result is entered, at the latest there. So
// where every ray starts outside every operand, its nearest surface (the
// first peeled layer) is all the result can show of it. Not for a leaf with
// a shell of no volume (SceneBuffers: solidShells): there the nearest entry
// can have an exit at its very depth, which the first layer would lose.
std::vector<char> reachedByUnionsOnly(const csg::CompiledTree& compiled, const SceneBuffers& scene) {
    std::vector<char> out(compiled.operandLeaf.size(), 0);
    if (compiled.code.empty()) return out;
    using Operands = std::vector<std::uint32_t>;
    auto literal = [](std::uint32_t instruction) {
        return instruction & csg::kOpNegate ? Operands{} : Operands{instruction >> csg::kOperandShift};
    };
    auto combine = [](std::uint32_t op, Operands& top, Operands&& source) {
        if (op == csg::kOpAnd) {
            top.clear();
        } else {
            top.insert(top.end(), source.begin(), source.end());
        }
    };
    for (std::uint32_t k : csg::foldCode<Operands>(compiled.code, literal, combine))
        out[k] = scene.leaf(compiled.operandLeaf[k]).solidShells ? 1 : 0;
    return out;
}

// Flips the row order in place: GL's bottom-up rows into image rows, top
// first, and back.
template <class T>
void flipRows(std::span<T> rows, int width, int height, int channels) {
    const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
    for (int y = 0; y < height / 2; ++y) {
        const auto top = rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y));
        const auto bottom = rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(height - 1 - y));
        std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(row), bottom);
    }
}

// Tiles cut for the operands' coverage (RenderSettings::coverageTilingFrom)
// are at least this many pixels a side.
constexpr int kSmallestCoverageTile = 64;

// `tile` cut in four on the evaluator's block grid: each side of at least two
// blocks is halved (rounded up to whole blocks), a shorter one is kept, so
// no tile is thinner than a block unless the frame is. Empty parts are left
// out; a tile that cannot be cut comes back alone.
std::vector<PixelRect> quarters(const PixelRect& tile) {
    auto half = [](int size) {
        const int b = EvaluatePass::kBlock;
        return size >= 2 * b ? (size / 2 + b - 1) / b * b : size;
    };
    const int w0 = half(tile.width), h0 = half(tile.height);
    std::vector<PixelRect> parts;
    for (const PixelRect& part : {PixelRect{tile.x + w0, tile.y + h0, tile.width - w0, tile.height - h0},
                                  PixelRect{tile.x, tile.y + h0, w0, tile.height - h0},
                                  PixelRect{tile.x + w0, tile.y, tile.width - w0, h0},
                                  PixelRect{tile.x, tile.y, w0, h0}}) {
        if (!part.empty()) parts.push_back(part);
    }
    return parts;
}

// The fixed-function state every pass of a frame starts from.
void resetDrawState() {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

}  // namespace

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
    Compilation separate, grouped, unionGrouped;
    std::size_t unionOnlyOperands = 0;  // the operands groupUnionOperands may join (RenderSettings::unionGroupFrom)
    const Compilation* current = nullptr;
    const Compilation& compilation(TreeForm form) const {
        return form == TreeForm::Separate ? separate : form == TreeForm::Grouped ? grouped : unionGrouped;
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

    Impl() { glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize); }

    // Renderer::setScene's; `release` (`model` itself, or null): let the
    // meshes go as they reach the GPU.
    void setScene(const scene::Tree& tree, const geometry::Model& model, geometry::Model* release);

    // A plain frame (PlainPass.h) in place of the peel, evaluate and normal passes.
    // `drawn` holds every pixel its leaves cover.
    // `litAs`: also light it as drawn, into the cleared image (no outline).
    void drawPlain(const ViewSetup& view, const PixelRect& drawn, const std::vector<glm::vec2>& baseColors,
                   const PlainPass::Output& output, Frame& frame);
    // Every pass; the images stay on the GPU. Fills frame's size and stats.
    // `aovs`: the depth, normal and leaf images will be read back.
    ViewSetup drawFrame(const Camera& camera, const RenderSettings& settings, Frame& frame, bool aovs);
    // The frame's view; throws strata::Error before setScene, for a negative
    // layer count, or for an image larger than the GPU's largest texture.
    ViewSetup frameView(const Camera& camera, const RenderSettings& settings) const;
    // Where a frame's operands lie on screen (drawFrame's, for peelAndEvaluate).
    struct ScreenRects {
        std::vector<PixelRect> rects;      // each operand's screen rectangle
        std::vector<int> markLeaves;       // the leaves that hold mark slots
        std::vector<PixelRect> markRects;  // and their screen rectangles
        PixelRect drawn;                   // every pixel the frame draws: all of the above
    };
    ScreenRects screenRects(const ViewSetup& view, const csg::CompiledTree& compiled, bool plainFrame) const;
    // The frame's plan (FramePlan.h) from what this renderer knows of its scene.
    FramePlan planFrame(const ViewSetup& view, const RenderSettings& settings, bool aovs) const;
    // `rects`: each operand's screen rectangle (screenRect of its vertices).
    // `markLeaves`, `markRects`: the leaves that hold mark slots (operands,
    // and a group's members in its place) and their screen rectangles.
    // `baseColors`: ShadePass::baseColors for this frame's colour scheme.
    // `litAs`: the normal pass lights the surfaces into the image, which
    // the caller has cleared to the background (NormalPass.h).
    void peelAndEvaluate(const ViewSetup& view, const std::vector<PixelRect>& rects, const std::vector<int>& markLeaves,
                         const std::vector<PixelRect>& markRects, const RenderSettings& settings,
                         const std::vector<glm::vec2>& baseColors, const std::optional<Lighting>& litAs,
                         Frame& frame);
    // What every tile of a frame reads (peelAndEvaluate's arguments).
    struct TileInputs {
        const ViewSetup& view;
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
    // The tile grid the frame starts from (see planTiles' body); throws
    // strata::Error where even the smallest tile's layers exceed the budget.
    struct TilePlan {
        std::vector<PixelRect> grid;
        std::size_t budgetTiles = 1;     // tiles the budget alone asks
        std::size_t wholeLayerBytes = 0; // the layers' estimate for the frame in one tile
    };
    TilePlan planTiles(const TileInputs& in) const;
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
    void shadeFrame(const ViewSetup& view, const ColorScheme& scheme, const RenderSettings& settings,
                    const std::optional<PixelRect>& marked, bool lit = false);
    void readColor(Frame& frame);  // the shaded image into frame.rgba, rows top first
    void readBack(Frame& frame, const RenderSettings& settings);  // what settings.read* ask, beside image and leaves
};

void Renderer::Impl::shadeFrame(const ViewSetup& view, const ColorScheme& scheme, const RenderSettings& settings,
                                const std::optional<PixelRect>& marked, bool lit) {
    if (!lit) shade->run(targets, view, scheme, settings.lighting, settings.outline, marked);
    if (!alphaLeaves.empty()) alpha->run(targets, scene, view, scheme, settings.lighting, alphaLeaves);
    if (!translucentLeaves.empty()) translucent->run(targets, scene, view, translucentLeaves);
    glFinish();
}

void Renderer::Impl::readColor(Frame& frame) {
    frame.rgba.resize(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 4);
    targets.color.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(frame.rgba)));
    flipRows(std::span(frame.rgba), frame.width, frame.height, 4);
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

void Renderer::setScene(const scene::Tree& tree, const geometry::Model& model) {
    impl_->setScene(tree, model, nullptr);
}

void Renderer::setScene(const scene::Tree& tree, geometry::Model&& model) {
    impl_->setScene(tree, model, &model);
    model = {};
}

void Renderer::Impl::setScene(const scene::Tree& tree, const geometry::Model& model, geometry::Model* release) {
    Impl& impl = *this;
    impl.scene.describe(tree, model);
    std::vector<bool> empty(model.leafMeshes.size());
    for (std::size_t i = 0; i < empty.size(); ++i) empty[i] = model.leafMeshes[i].triangles.empty();
    const std::vector<int> same = csg::identicalLeaves(tree, model);
    impl.copiedLeaves = 0;
    for (std::size_t i = 0; i < same.size(); ++i) impl.copiedLeaves += same[i] != static_cast<int>(i) ? 1 : 0;
    impl.separate.tree = csg::compileTree(tree, empty, same);
    impl.separate.unionsOnly = reachedByUnionsOnly(impl.separate.tree, impl.scene);
    std::vector<char> convex(impl.separate.tree.operandLeaf.size());
    for (std::size_t k = 0; k < convex.size(); ++k) {
        convex[k] = impl.scene.leaf(impl.separate.tree.operandLeaf[k]).convex ? 1 : 0;
    }
    impl.grouped.tree = csg::groupConvexProducts(impl.separate.tree, convex, PeelRequest::kMostGroupMembers);
    // The groups that ask whether their members share a plane (GroupPeel::tiesWanted).
    for (const std::vector<int>& members : impl.grouped.tree.operandGroups) {
        if (members.size() > GroupPeel::kMostTieMembers) impl.scene.hashPlanes(model, members);
    }
    impl.grouped.unionsOnly = reachedByUnionsOnly(impl.grouped.tree, impl.scene);
    // Of those, the ones that only unions lead to, a group per run
    // (groupUnionOperands): right only where every ray starts outside.
    std::vector<char> unitable(impl.grouped.unionsOnly);
    impl.unionOnlyOperands = 0;
    for (std::size_t k = 0; k < unitable.size(); ++k) {
        if (impl.grouped.tree.leavesOf(k).size() > 1) unitable[k] = 0;
        impl.unionOnlyOperands += unitable[k] ? 1 : 0;
    }
    impl.unionGrouped.tree =
        csg::groupUnionOperands(impl.grouped.tree, unitable, PeelRequest::kMostUnionMembers);
    impl.unionGrouped.unionsOnly = reachedByUnionsOnly(impl.unionGrouped.tree, impl.scene);
    // Last, once nothing above needs the meshes any more.
    impl.scene.fill(model, release);
    impl.plainLeaves = PlainPass::plainLeaves(impl.separate.tree, impl.scene);
    impl.plainStale = true;
    // The evaluator takes its tree at the first frame that needs one.
    impl.current = nullptr;
    impl.translucentLeaves = render::translucentLeaves(tree, impl.scene);
    impl.alphaLeaves = render::alphaLeaves(tree, impl.scene);
    impl.leafCount = tree.leaves.size();
    impl.hasScene = true;
    gpu::checkErrors();
}

void Renderer::Impl::peelAndEvaluate(const ViewSetup& view, const std::vector<PixelRect>& rects,
                                     const std::vector<int>& markLeaves, const std::vector<PixelRect>& markRects,
                                     const RenderSettings& settings, const std::vector<glm::vec2>& baseColors,
                                     const std::optional<Lighting>& litAs, Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    const std::vector<int>& operands = compiled.operandLeaf;
    if (targets.leafMarks) targets.assignMarkSlots(markLeaves, markRects, leafCount);
    PeelRequest request{settings.layers, settings.memoryBudget, {}, settings.fragmentListTriangles,
                        compiled.operandGroups, compiled.unionGroups};
    // Every ray starts outside every operand: those that only unions lead to
    // need their first layer alone (the debug views show every layer).
    if (beyondNearPlane(view, scene.bounds()) && !settings.keepPeelLayers && roundSink == nullptr) {
        request.firstLayerOnly = current->unionsOnly;
    }
    // Each single leaf's hull on the screen, which the evaluator's blocks
    // test besides the rectangle: a thin bar seen aslant (a Menger sponge's)
    // reaches a few blocks of the many its rectangle holds. Groups, and
    // leaves of many vertices, keep their rectangle alone.
    constexpr std::size_t kMostHullVertices = 4096;
    std::vector<ScreenHull> hulls(operands.size());
    for (std::size_t k = 0; k < operands.size() && settings.screenHulls; ++k) {
        if (compiled.leavesOf(k).size() != 1 || compiled.isUnionGroup(k)) continue;
        hulls[k] = screenHull(view, scene.leafVertices(operands[k]), kMostHullVertices);
    }
    const TileInputs in{view, rects, hulls, markLeaves, markRects, settings, baseColors, request, litAs};
    const TilePlan plan = planTiles(in);
    const std::vector<PixelRect>& grid = plan.grid;
    const TileCounts counts = runTiles(in, grid, frame);
    stats.tiles = counts.drawn;
    std::sort(frame.peelLayers.begin(), frame.peelLayers.end(), [](const PeelLayerImage& a, const PeelLayerImage& b) {
        return a.leaf != b.leaf ? a.leaf < b.leaf : a.layer < b.layer;
    });
    if (plan.budgetTiles > 1) {
        stats.notes.push_back("peel layers for every operand at " + std::to_string(view.width) + "x" +
                              std::to_string(view.height) + " would exceed the budget of " +
                              mebibytes(settings.memoryBudget) + ": rendered in " + std::to_string(counts.drawn) +
                              " tiles, each peeling only the operands that meet it");
    } else if (grid.size() > 1) {
        stats.notes.push_back("rendered in " + std::to_string(counts.drawn) +
                              " tiles, each peeling only the operands that meet it: " +
                              mebibytes(stats.textureBytes) + " of layers instead of " +
                              mebibytes(plan.wholeLayerBytes) + " for the whole frame");
    }
    if (counts.splits > 0) {
        stats.notes.push_back("auto peeling needed more layers than estimated: split " +
                              std::to_string(counts.splits) + " tiles to stay within " +
                              mebibytes(settings.memoryBudget));
    }
    if (settings.layers > 1) {
        const bool anyConvex = std::any_of(operands.begin(), operands.end(),
                                           [&](int leaf) { return scene.leaf(leaf).convex; });
        if (anyConvex) stats.notes.push_back("convex operands peeled once: a second layer would be empty");
    }
}

Renderer::Impl::TilePlan Renderer::Impl::planTiles(const TileInputs& in) const {
    // The whole frame, or an even grid of quarters, of quarters of those,
    // ..., as fine as the densest tile needs for the layers its operands
    // need (a first guess for auto) to fit the budget. Only the operands
    // whose rectangle meets a tile are peeled for it, so memory follows the
    // operands per tile, not their number in the frame. One tile size for
    // the whole frame lets every tile (and the next frame) reuse one layer
    // texture: llvmpipe zeroes each new texture, and a fresh 512 MiB costs
    // more than the peel of several extra tiles.
    const std::vector<int>& operands = current->tree.operandLeaf;
    const std::size_t budget = in.settings.memoryBudget;
    std::vector<char> inTile(operands.size());
    auto area = [](const PixelRect& tile) {
        return static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height);
    };
    // A grid and each of its tiles' estimates, made once per grid.
    struct Grid {
        std::vector<PixelRect> tiles;
        std::vector<PeelPass::LayerEstimate> estimates;
    };
    auto withEstimates = [&](std::vector<PixelRect> tiles) {
        Grid grid{std::move(tiles), {}};
        for (const PixelRect& tile : grid.tiles) {
            for (std::size_t k = 0; k < operands.size(); ++k) inTile[k] = in.rects[k].intersects(tile) ? 1 : 0;
            grid.estimates.push_back(PeelPass::estimateLayers(scene, operands, inTile, in.request));
        }
        return grid;
    };
    auto bytes = [&](const Grid& grid, std::size_t t) { return grid.estimates[t].bytesPerPixel() * area(grid.tiles[t]); };
    auto quartered = [](const Grid& grid) {
        std::vector<PixelRect> parts;
        for (const PixelRect& tile : grid.tiles) {
            for (const PixelRect& part : quarters(tile)) parts.push_back(part);
        }
        return parts;
    };
    Grid grid = withEstimates({PixelRect{0, 0, in.view.width, in.view.height}});
    TilePlan plan;
    plan.wholeLayerBytes = bytes(grid, 0);
    for (;;) {
        std::size_t over = 0;
        while (over < grid.tiles.size() && bytes(grid, over) <= budget) ++over;
        if (over == grid.tiles.size()) break;
        std::vector<PixelRect> parts = quartered(grid);
        if (parts.size() == grid.tiles.size()) {  // no tile can be cut: `over` is as small as tiles get
            const PeelPass::LayerEstimate& estimate = grid.estimates[over];
            const std::size_t perPixel = estimate.bytesPerPixel();
            throw Error("renderer: a memory budget of " + mebibytes(budget) + " holds " + std::to_string(estimate.layers) +
                        " peel layers for only " + std::to_string(budget / perPixel) +
                        " pixels at a time; give it at least " + mebibytes(perPixel * area(grid.tiles[over])));
        }
        grid = withEstimates(std::move(parts));
    }
    // Within the budget, finer still while the layers take more than
    // coverageTilingFrom and the operands are small on screen: a quarter then
    // peels only the few that meet it, so its layers shrink by far more
    // than the area, for a few more draws (at most coverageTilingDraws
    // times as many a step). Operands that span the frame would be drawn
    // once per tile for a quarter of the memory each, and stay whole.
    auto draws = [](const Grid& g) {
        std::size_t sum = 0;
        for (const PeelPass::LayerEstimate& e : g.estimates) sum += static_cast<std::size_t>(e.layers);
        return sum;
    };
    auto layerBytes = [&](const Grid& g) {
        std::size_t most = 0;
        for (std::size_t t = 0; t < g.tiles.size(); ++t) most = std::max(most, bytes(g, t));
        return most;
    };
    plan.budgetTiles = grid.tiles.size();
    while (layerBytes(grid) > in.settings.coverageTilingFrom) {
        std::vector<PixelRect> parts = quartered(grid);
        const bool small = std::any_of(parts.begin(), parts.end(), [](const PixelRect& tile) {
            return std::min(tile.width, tile.height) < kSmallestCoverageTile;
        });
        if (parts.size() == grid.tiles.size() || small) break;
        Grid cut = withEstimates(std::move(parts));
        if (static_cast<double>(draws(cut)) > in.settings.coverageTilingDraws * static_cast<double>(draws(grid))) break;
        grid = std::move(cut);
    }
    plan.grid = std::move(grid.tiles);
    return plan;
}

Renderer::Impl::TileCounts Renderer::Impl::runTiles(const TileInputs& in, const std::vector<PixelRect>& grid,
                                                    Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    const std::vector<int>& operands = compiled.operandLeaf;
    std::deque<PixelRect> tiles(grid.begin(), grid.end());
    std::vector<OperandLayers> layers;
    TileCounts counts;
    while (!tiles.empty()) {
        // Every tile fits the budget by its estimate: the grid's, and their
        // quarters (fewer operands, fewer pixels) split off below.
        const PixelRect tile = tiles.front();
        tiles.pop_front();

        const auto start = Clock::now();
        const bool fits = peel->run(scene, in.view, tile, operands, in.rects, EvaluatePass::kBlock, in.request, layers);
        glFinish();
        stats.peelMs += msSince(start);
        stats.textureBytes = std::max(stats.textureBytes, peel->textureBytes());
        stats.textureAllocations += peel->allocations();
        stats.peelPasses += peel->passes();
        stats.listPeeledOperands += peel->collected();
        if (!fits) {
            if (quarters(tile).size() == 1) {
                throw Error("renderer: the scene needs more peel layers at one spot than " +
                            std::string("the memory budget of ") + mebibytes(in.settings.memoryBudget) +
                            " and the GPU's " + std::to_string(peel->maxArrayLayers()) + " array layers allow");
            }
            // Auto peeling went deeper than guessed: split the tile in four.
            for (const PixelRect& part : quarters(tile)) tiles.push_front(part);
            ++counts.splits;
            continue;
        }
        for (std::size_t k = 0; k < operands.size(); ++k) {
            for (int leaf : compiled.leavesOf(k)) {
                int& used = stats.layersPerLeaf[static_cast<std::size_t>(leaf)];
                used = std::max(used, layers[k].count);
            }
        }
        if (in.settings.keepPeelLayers) keepLayers(tile, operands, in.rects, layers, frame);
        if (roundSink != nullptr) {
            peelResultRounds(in, tile, layers, frame);
        } else {
            evaluateTile(in, tile, layers, frame);
        }
        ++counts.drawn;
    }
    return counts;
}

void Renderer::Impl::evaluateTile(const TileInputs& in, const PixelRect& tile, const std::vector<OperandLayers>& layers,
                                  Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    auto start = Clock::now();
    std::vector<BlockForm> forms;
    evaluate->run(targets, peel->layers(), tile, layers, in.rects, in.hulls, EvaluatePass::groupTable(leafCount, compiled, layers),
                 peel->groupIds(), in.settings.generalEvaluator, in.view.coincidence, stats,
                 in.settings.keepBlockForms ? &forms : nullptr);
    if (in.settings.keepBlockForms) keepBlockForms(tile, forms, frame);
    const std::vector<std::uint32_t> shown = evaluate->shownFaces();  // waits for the evaluator
    stats.evaluateMs += msSince(start);
    start = Clock::now();
    normals->run(targets, scene, in.view, tile, compiled, in.rects, shown, in.baseColors, in.markLeaves, in.markRects,
                 in.litAs);
    glFinish();
    stats.normalMs += msSince(start);
}

void Renderer::Impl::peelResultRounds(const TileInputs& in, const PixelRect& tile,
                                      const std::vector<OperandLayers>& layers, Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    const std::vector<int> groups = EvaluatePass::groupTable(leafCount, compiled, layers);
    const float before = -std::numeric_limits<float>::infinity();
    glClearTexSubImage(resultStart.id(), 0, tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED, GL_FLOAT, &before);
    const std::size_t n = static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height);
    std::vector<float> depth(n), normal(n * 4);
    std::vector<std::int32_t> leaf(n);
    std::vector<glm::vec3> outward(n);
    for (int round = 0;; ++round) {
        auto start = Clock::now();
        targets.clearRegion(tile);
        evaluate->runResultRound(targets, peel->layers(), tile, layers, in.rects, in.hulls, groups, peel->groupIds(), resultStart,
                                round > 0, in.view.coincidence, stats);
        const std::vector<std::uint32_t> shown = evaluate->shownFaces();  // waits for the evaluator
        stats.evaluateMs += msSince(start);
        start = Clock::now();
        normals->run(targets, scene, in.view, tile, compiled, in.rects, shown, in.baseColors, in.markLeaves,
                     in.markRects, std::nullopt);  // the normals are read back
        glFinish();
        stats.normalMs += msSince(start);

        start = Clock::now();
        targets.resultLeaf.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED_INTEGER, GL_INT,
                                          std::as_writable_bytes(std::span(leaf)));
        ResultRound out{round, tile.x, frame.height - (tile.y + tile.height), tile.width, tile.height, {}, {}, 0};
        std::size_t found = 0;
        for (std::int32_t code : leaf) {
            found += code >= 0 ? 1 : 0;
            out.unresolved += code == shader::kLeafUnresolved ? 1 : 0;
        }
        stats.unresolvedPixels += out.unresolved;
        if (found == 0) {
            stats.readbackMs += msSince(start);
            return;
        }
        stats.coveredPixels += found;
        targets.resultDepth.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED, GL_FLOAT,
                                           std::as_writable_bytes(std::span(depth)));
        targets.normal.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RGBA, GL_FLOAT,
                                      std::as_writable_bytes(std::span(normal)));
        // The next round walks on from each pixel's change (+inf: none left).
        glCopyImageSubData(targets.resultDepth.id(), GL_TEXTURE_2D, 0, tile.x, tile.y, 0, resultStart.id(),
                           GL_TEXTURE_2D, 0, tile.x, tile.y, 0, tile.width, tile.height, 1);
        flipRows(std::span(depth), tile.width, tile.height, 1);
        flipRows(std::span(normal), tile.width, tile.height, 4);
        flipRows(std::span(leaf), tile.width, tile.height, 1);
        for (std::size_t i = 0; i < n; ++i) {
            if (leaf[i] < 0) depth[i] = std::numeric_limits<float>::infinity();
            outward[i] = {normal[i * 4], normal[i * 4 + 1], normal[i * 4 + 2]};
        }
        out.depth = depth;
        out.normal = outward;
        stats.readbackMs += msSince(start);
        (*roundSink)(out);
    }
}

void Renderer::Impl::keepBlockForms(const PixelRect& tile, const std::vector<BlockForm>& forms, Frame& frame) {
    if (forms.empty()) return;  // nothing drawn in the tile
    const std::size_t w = static_cast<std::size_t>(frame.width);
    constexpr int block = EvaluatePass::kBlock;
    const int blocksX = (tile.width + block - 1) / block;
    for (int y = 0; y < tile.height; ++y) {
        const std::size_t row = static_cast<std::size_t>(frame.height - 1 - (tile.y + y));  // rows top first
        for (int x = 0; x < tile.width; ++x) {
            const std::size_t b = static_cast<std::size_t>((y / block) * blocksX + x / block);
            frame.blockForms[row * w + static_cast<std::size_t>(tile.x + x)] = forms[b];
        }
    }
}

void Renderer::Impl::keepLayers(const PixelRect& tile, const std::vector<int>& operands,
                                const std::vector<PixelRect>& rects, const std::vector<OperandLayers>& layers,
                                Frame& frame) {
    const std::size_t n = static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
    const float none = std::numeric_limits<float>::infinity();
    std::vector<float> texels(static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height) * 2);
    for (std::size_t k = 0; k < operands.size(); ++k) {
        for (int l = 0; l < layers[k].count; ++l) {
            auto it = std::find_if(frame.peelLayers.begin(), frame.peelLayers.end(), [&](const PeelLayerImage& p) {
                return p.leaf == operands[k] && p.layer == l;
            });
            if (it == frame.peelLayers.end()) {
                frame.peelLayers.push_back({operands[k], l, std::vector<float>(n, none), std::vector<float>(n, none)});
                it = frame.peelLayers.end() - 1;
            }
            const PixelRect valid = PeelPass::region(rects[k], tile, EvaluatePass::kBlock);
            if (valid.empty()) continue;
            peel->layers().downloadRegion(valid.x, valid.y, layers[k].first + l, valid.width, valid.height, 1, GL_RG,
                                         GL_FLOAT, std::as_writable_bytes(std::span(texels)));
            for (int y = valid.y; y < valid.y + valid.height; ++y) {
                for (int x = valid.x; x < valid.x + valid.width; ++x) {
                    const std::size_t from =
                        (static_cast<std::size_t>(y - valid.y) * static_cast<std::size_t>(valid.width) +
                         static_cast<std::size_t>(x - valid.x)) * 2;
                    // GL rows count from the bottom; image rows from the top.
                    const std::size_t to = static_cast<std::size_t>(frame.height - 1 - (tile.y + y)) * frame.width +
                                           static_cast<std::size_t>(tile.x + x);
                    const float nearValue = -texels[from], farValue = texels[from + 1];
                    it->nearDepth[to] = nearValue >= shader::kClearedDepth ? none : nearValue;
                    it->farDepth[to] = farValue <= -shader::kClearedDepth ? none : farValue;
                }
            }
        }
    }
}

void Renderer::Impl::readBack(Frame& frame, const RenderSettings& settings) {
    // Straight into the frame's own arrays, flipped in place: a 1024x768
    // frame's read-back then holds no copies beside them.
    const int w = frame.width, h = frame.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);

    readColor(frame);

    if (settings.readDepth) {
        frame.depth.resize(n);
        targets.resultDepth.download(GL_RED, GL_FLOAT, std::as_writable_bytes(std::span(frame.depth)));
        flipRows(std::span(frame.depth), w, h, 1);
    }

    frame.leaf.resize(n);
    targets.resultLeaf.download(GL_RED_INTEGER, GL_INT, std::as_writable_bytes(std::span(frame.leaf)));
    flipRows(std::span(frame.leaf), w, h, 1);
    for (std::int32_t& code : frame.leaf) {
        if (code >= 0) ++frame.stats.coveredPixels;
        if (code == shader::kLeafUnresolved) ++frame.stats.unresolvedPixels;
        code = shader::leafOfCode(code);
    }
    if (frame.stats.unresolvedPixels > 0) {
        frame.stats.notes.push_back(std::to_string(frame.stats.unresolvedPixels) +
                                    " pixels had more surfaces than this driver lets one shader walk "
                                    "(llvmpipe's loop limit); they are drawn empty");
    }

    if (settings.readNormal) {
        static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");
        frame.normal.resize(n);
        targets.normal.download(GL_RGB, GL_FLOAT, std::as_writable_bytes(std::span(frame.normal)));
        flipRows(std::span(frame.normal), w, h, 1);
    }
    gpu::checkErrors();
}

void Renderer::Impl::drawPlain(const ViewSetup& view, const PixelRect& drawn,
                               const std::vector<glm::vec2>& baseColors, const PlainPass::Output& output,
                               Frame& frame) {
    FrameStats& stats = frame.stats;
    const auto start = Clock::now();
    if (plainStale) {
        plain->setLeaves(scene, plainLeaves);
        plainStale = false;
    }
    plain->run(targets, scene, view, drawn, baseColors, output);
    glFinish();
    stats.plainMs = msSince(start);
    stats.plain = true;
    stats.tiedLeaves = plain->tiedLeaves();
    stats.tiedTriangles = plain->tiedTriangles();
    stats.operands = static_cast<int>(plainLeaves.size());
    stats.tiles = 1;
    stats.notes.push_back("drawn plainly: a union of " + std::to_string(plainLeaves.size()) +
                          (plainLeaves.size() == 1 ? " leaf" : " leaves") +
                          " seen from outside, depth-tested with no peel or evaluator");
}

ViewSetup Renderer::Impl::frameView(const Camera& camera, const RenderSettings& settings) const {
    if (!hasScene) throw Error("renderer: render() before setScene()");
    if (settings.layers < 0) throw Error("renderer: layers must be 0 (auto) or positive");
    ViewSetup view = makeView(camera, scene.bounds());
    // The result peel (sampleResult) runs its rays along the model's axes,
    // on grids that put rays exactly along a solid's silhouette edges,
    // where the rasterizer's depths of the front and back faces that meet
    // there (interpolated from vertices snapped to its sub-pixel grid) part
    // by up to 2^-17 of the scene's scale: a chord that exact arithmetic
    // gives no length. Its cells are far coarser than that, so it takes
    // sixteen times the tolerance of an image.
    if (roundSink != nullptr) view.coincidence *= 16.0;
    if (view.width > maxTextureSize || view.height > maxTextureSize) {
        throw Error("renderer: image size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                    " exceeds the GPU's largest texture, " + std::to_string(maxTextureSize));
    }
    return view;
}

Renderer::Impl::ScreenRects Renderer::Impl::screenRects(const ViewSetup& view, const csg::CompiledTree& compiled,
                                                        bool plainFrame) const {
    // Each operand's screen rectangle: its surfaces, and so every pixel the
    // evaluator can mark, lie inside it.
    // Mark slots go to the operands, a group's to each of its members.
    ScreenRects out;
    if (plainFrame) {
        for (int leaf : plainLeaves) out.drawn = out.drawn.bounding(screenRect(view, scene.leafVertices(leaf)));
    } else if (compiled.kind == csg::CompiledTree::Kind::Code) {
        out.rects.resize(compiled.operandLeaf.size());
        for (std::size_t k = 0; k < out.rects.size(); ++k) {
            // An intersection's surfaces lie where all its members' do, a
            // union's where any member's does.
            const std::span<const int> leaves = compiled.leavesOf(k);
            const bool unite = compiled.isUnionGroup(k);
            for (std::size_t i = 0; i < leaves.size(); ++i) {
                const PixelRect own = screenRect(view, scene.leafVertices(leaves[i]));
                out.rects[k] = i == 0 ? own : unite ? out.rects[k].bounding(own) : out.rects[k].intersection(own);
                out.markLeaves.push_back(leaves[i]);
                out.markRects.push_back(own);
            }
            out.drawn = out.drawn.bounding(out.rects[k]);
        }
    }
    return out;
}

FramePlan Renderer::Impl::planFrame(const ViewSetup& view, const RenderSettings& settings, bool aovs) const {
    FrameFacts facts;
    facts.outside = beyondNearPlane(view, scene.bounds());
    facts.plainScene = !plainLeaves.empty();
    facts.resultPeel = roundSink != nullptr;
    facts.aovs = aovs;
    facts.unionOnlyOperands = unionOnlyOperands;
    for (const TreeForm form : {TreeForm::Separate, TreeForm::Grouped, TreeForm::UnionGrouped})
        facts.kinds[static_cast<std::size_t>(form)] = compilation(form).tree.kind;
    return render::planFrame(facts, settings);
}

ViewSetup Renderer::Impl::drawFrame(const Camera& camera, const RenderSettings& settings, Frame& frame,
                                    bool aovs) {
    const auto frameStart = Clock::now();
    const ViewSetup view = frameView(camera, settings);
    const ColorScheme& scheme = colorScheme(settings.colorScheme);

    frame.width = view.width;
    frame.height = view.height;
    FrameStats& stats = frame.stats;
    stats.layersPerLeaf.assign(leafCount, 0);
    if (settings.keepBlockForms) {
        frame.blockForms.assign(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height),
                                BlockForm::None);
    }
    const FramePlan plan = planFrame(view, settings, aovs);
    const Compilation& chosen = compilation(plan.form);
    if (current != &chosen && !plan.plainFrame) {
        evaluate->setTree(chosen.tree, canMarkLeaves);
        current = &chosen;
    }
    const csg::CompiledTree& compiled = chosen.tree;
    stats.operands = compiled.operandCount();
    stats.tiles = 0;
    stats.peelPasses = 0;
    const ScreenRects screen = screenRects(view, compiled, plan.plainFrame);

    resetDrawState();
    targets.ensure(view.width, view.height);
    // A pixel around `drawn` for the shade pass's Sobel filter.
    // The translucent and alpha passes read the result beyond the marked pixels.
    if (!plan.shownOnly) {
        using NormalClear = FrameTargets::NormalClear;
        targets.clearResult(aovs || !translucentLeaves.empty() || !alphaLeaves.empty(),
                            plan.aovNormals                       ? NormalClear::WholeFrame
                            : plan.evaluated && plan.litAsDrawn ? NormalClear::None
                                                                : NormalClear::Drawn,
                            screen.drawn.grown(1));
    }
    targets.leafMarks = settings.leafMarks && canMarkLeaves;
    targets.plainFrame = plan.plainFrame;
    if (copiedLeaves > 0) {
        stats.notes.push_back(std::to_string(copiedLeaves) +
                              (copiedLeaves == 1 ? " leaf repeats a lower one exactly and shares its peeled layers"
                                                 : " leaves repeat lower ones exactly and share their peeled layers"));
    }
    std::optional<Lighting> litAs;
    if (plan.litAsDrawn) litAs = settings.lighting;
    stats.litAsDrawn = plan.litAsDrawn;
    if (plan.plainFrame) {
        PlainPass::Output output;
        output.litAs = litAs;
        output.shownOnly = plan.shownOnly;
        output.background = glm::vec4(glm::vec3(scheme.background), 1.0f);
        output.keepResult = !translucentLeaves.empty() || !alphaLeaves.empty();
        drawPlain(view, screen.drawn, ShadePass::baseColors(scene, scheme), output, frame);
    } else if (plan.evaluated) {
        if (plan.litAsDrawn) {
            // The normal pass lights only the pixels the result covers.
            const float background[4] = {scheme.background.r, scheme.background.g, scheme.background.b, 1.0f};
            glClearNamedFramebufferfv(targets.colorTarget.id(), GL_COLOR, 0, background);
        }
        peelAndEvaluate(view, screen.rects, screen.markLeaves, screen.markRects, settings,
                        ShadePass::baseColors(scene, scheme), litAs, frame);
    } else {
        stats.notes.push_back(compiled.kind == csg::CompiledTree::Kind::Empty ? "the CSG result is empty"
                                                                        : "the CSG result is everything");
    }

    if (roundSink == nullptr) {
        const auto start = Clock::now();
        shadeFrame(view, scheme, settings, screen.drawn, plan.litAsDrawn);
        stats.shadeMs = msSince(start);
    }
    stats.totalMs = msSince(frameStart);
    return view;
}

Frame Renderer::render(const Camera& camera, const RenderSettings& settings) {
    Frame frame;
    impl_->drawFrame(camera, settings, frame, true);
    const auto start = Clock::now();
    impl_->readBack(frame, settings);
    frame.stats.readbackMs = msSince(start);
    frame.stats.totalMs += frame.stats.readbackMs;
    return frame;
}

FrameStats Renderer::sampleResult(const Camera& camera, const RenderSettings& settings,
                                  const std::function<void(const ResultRound&)>& onRound) {
    Impl& impl = *impl_;
    if (camera.width <= 0 || camera.height <= 0) throw Error("renderer: sampleResult() needs a positive image size");
    if (impl.resultStart.id() == 0 || impl.resultStart.width() != camera.width ||
        impl.resultStart.height() != camera.height) {
        impl.resultStart = gpu::Texture::create2D("result peel start", GL_R32F, camera.width, camera.height);
    }
    RenderSettings peeled = settings;
    peeled.keepPeelLayers = false;
    peeled.keepBlockForms = false;
    impl.roundSink = &onRound;
    Frame frame;
    try {
        impl.drawFrame(camera, peeled, frame, true);
    } catch (...) {
        impl.roundSink = nullptr;
        throw;
    }
    impl.roundSink = nullptr;
    return frame.stats;
}

Frame Renderer::shade(const Camera& camera, const RenderSettings& settings, const ExternalResult& result) {
    Impl& impl = *impl_;
    if (!impl.hasScene) throw Error("renderer: shade() before setScene()");
    const auto frameStart = Clock::now();
    const ColorScheme& scheme = colorScheme(settings.colorScheme);
    const ViewSetup view = makeView(camera, impl.scene.bounds());
    const int w = view.width, h = view.height;
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (result.depth.size() != n || result.normal.size() != n || result.leaf.size() != n || result.cut.size() != n)
        throw Error("renderer: shade() needs width * height values in every AOV");

    // The G-buffer as the normal pass writes it, then flipped to GL's bottom-up rows.
    const std::vector<glm::vec2> bases = ShadePass::baseColors(impl.scene, scheme);
    std::vector<float> depth(result.depth.begin(), result.depth.end());
    std::vector<float> normal(n * 4, 0.0f);
    std::vector<std::int32_t> codes(n, shader::kLeafMiss);
    for (std::size_t i = 0; i < n; ++i) {
        const int leaf = result.leaf[i];
        if (leaf < 0) continue;
        if (static_cast<std::size_t>(leaf) >= bases.size())
            throw Error("renderer: shade() got leaf " + std::to_string(leaf) + ", which the scene lacks");
        const glm::vec2 base = bases[static_cast<std::size_t>(leaf)];
        normal[i * 4 + 0] = result.normal[i].x;
        normal[i * 4 + 1] = result.normal[i].y;
        normal[i * 4 + 2] = result.normal[i].z;
        normal[i * 4 + 3] = result.cut[i] ? base.y : base.x;
        codes[i] = shader::leafCode(leaf, result.cut[i] != 0);
    }
    resetDrawState();
    impl.targets.ensure(w, h);
    impl.targets.plainFrame = false;
    flipRows(std::span(depth), w, h, 1);
    flipRows(std::span(normal), w, h, 4);
    flipRows(std::span(codes), w, h, 1);
    impl.targets.resultDepth.upload(0, 0, 0, w, h, 1, GL_RED, GL_FLOAT, depth.data());
    impl.targets.normal.upload(0, 0, 0, w, h, 1, GL_RGBA, GL_FLOAT, normal.data());
    impl.targets.resultLeaf.upload(0, 0, 0, w, h, 1, GL_RED_INTEGER, GL_INT, codes.data());

    Frame frame;
    frame.width = w;
    frame.height = h;
    const auto start = Clock::now();
    impl.shadeFrame(view, scheme, settings, std::nullopt);
    frame.stats.shadeMs = msSince(start);
    impl.readColor(frame);
    frame.depth.assign(result.depth.begin(), result.depth.end());
    frame.normal.assign(result.normal.begin(), result.normal.end());
    frame.leaf.assign(result.leaf.begin(), result.leaf.end());
    for (std::int32_t leaf : frame.leaf) frame.stats.coveredPixels += leaf >= 0 ? 1 : 0;
    gpu::checkErrors();
    frame.stats.totalMs = msSince(frameStart);
    return frame;
}

FrameStats Renderer::renderInto(unsigned framebuffer, int x, int y, const Camera& camera,
                                const RenderSettings& settings) {
    Frame frame;
    impl_->drawFrame(camera, settings, frame, false);
    const auto start = Clock::now();
    glBlitNamedFramebuffer(impl_->targets.colorTarget.id(), framebuffer, 0, 0, frame.width, frame.height, x, y,
                           x + frame.width, y + frame.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glFinish();
    gpu::checkErrors();
    frame.stats.readbackMs = msSince(start);
    frame.stats.totalMs += frame.stats.readbackMs;
    return frame.stats;
}

}  // namespace strata::render
