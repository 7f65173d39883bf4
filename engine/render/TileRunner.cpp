#include "RendererImpl.h"

namespace strata::render {

void Renderer::Impl::peelAndEvaluate(const ViewSetup& view, const FramePlan& plan, const std::vector<PixelRect>& rects,
                                     const std::vector<int>& markLeaves, const std::vector<PixelRect>& markRects,
                                     const RenderSettings& settings, const std::vector<glm::vec2>& baseColors,
                                     const std::optional<Lighting>& litAs, LeafRects& leafRects, Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    const std::vector<int>& operands = compiled.operandLeaf;
    if (targets.leafMarks) targets.assignMarkSlots(markLeaves, markRects, leafCount);
    PeelRequest request{settings.layers, settings.budget(), {}, settings.fragmentListTriangles,
                        compiled.operandGroups, compiled.unionGroups};
    if (plan.firstLayerOnly) request.firstLayerOnly = current->unionsOnly;
    // Each single leaf's hull on the screen, which the evaluator's blocks
    // test besides the rectangle: a thin bar seen aslant (a Menger sponge's)
    // reaches a few blocks of the many its rectangle holds. Groups, and
    // leaves of many vertices, keep their rectangle alone.
    std::vector<ScreenHull> hulls(operands.size());
    for (std::size_t k = 0; k < operands.size() && settings.screenHulls; ++k) {
        if (compiled.leavesOf(k).size() != 1 || compiled.isUnionGroup(k)) continue;
        hulls[k] = leafRects.hull(operands[k]);
    }
    const TileInputs in{view, plan, rects, hulls, markLeaves, markRects, settings, baseColors, request, litAs};
    const TileGrid tiles = planTiles(in);
    const std::vector<PixelRect>& grid = tiles.tiles;
    const TileCounts counts = runTiles(in, grid, frame);
    stats.tiles = counts.drawn;
    std::sort(frame.peelLayers.begin(), frame.peelLayers.end(), [](const PeelLayerImage& a, const PeelLayerImage& b) {
        return a.leaf != b.leaf ? a.leaf < b.leaf : a.layer < b.layer;
    });
    if (tiles.budgetTiles > 1) {
        stats.notes.push_back("peel layers for every operand at " + std::to_string(view.width) + "x" +
                              std::to_string(view.height) + " would exceed the budget of " +
                              mebibytes(settings.budget()) + ": rendered in " + std::to_string(counts.drawn) +
                              " tiles, each peeling only the operands that meet it");
    } else if (grid.size() > 1) {
        stats.notes.push_back("rendered in " + std::to_string(counts.drawn) +
                              " tiles, each peeling only the operands that meet it: " +
                              mebibytes(stats.textureBytes) + " of layers instead of " +
                              mebibytes(tiles.wholeLayerBytes) + " for the whole frame");
    }
    if (counts.splits > 0) {
        stats.notes.push_back("auto peeling needed more layers than estimated: split " +
                              std::to_string(counts.splits) + " tiles to stay within " +
                              mebibytes(settings.budget()));
    }
    if (settings.layers > 1) {
        const bool anyConvex = std::any_of(operands.begin(), operands.end(),
                                           [&](int leaf) { return scene.leaf(leaf).convex; });
        if (anyConvex) stats.notes.push_back("convex operands peeled once: a second layer would be empty");
    }
}

TileGrid Renderer::Impl::planTiles(const TileInputs& in) const {
    const std::vector<int>& operands = current->tree.operandLeaf;
    return planTileGrid(in.view.width, in.view.height, in.rects, in.settings, EvaluatePass::kBlock,
                        [&](const std::vector<char>& inTile) {
                            const PeelPass::LayerEstimate e = PeelPass::estimateLayers(scene, operands, inTile, in.request);
                            return TileEstimate{e.layers, e.bytesPerPixel()};
                        });
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
        passDone();
        stats.peelMs += msSince(start);
        stats.textureBytes = std::max(stats.textureBytes, peel->textureBytes());
        stats.textureAllocations += peel->allocations();
        stats.peelPasses += peel->passes();
        stats.listPeeledOperands += peel->collected();
        if (!fits) {
            if (quarters(tile, EvaluatePass::kBlock).size() == 1) {
                throw Error("renderer: the scene needs more peel layers at one spot than " +
                            std::string("the memory budget of ") + mebibytes(in.settings.budget()) +
                            " and the GPU's " + std::to_string(peel->maxArrayLayers()) + " array layers allow");
            }
            // Auto peeling went deeper than guessed: split the tile in four.
            for (const PixelRect& part : quarters(tile, EvaluatePass::kBlock)) tiles.push_front(part);
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
        if (in.plan.resultPeel) {
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
    passDone();
    stats.normalMs += msSince(start);
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

}  // namespace strata::render
