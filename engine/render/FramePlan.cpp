#include "FramePlan.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "strata/core/Error.h"

namespace strata::render {

namespace {

// Tiles cut for the operands' coverage (RenderSettings::coverageTilingFrom)
// are at least this many pixels a side.
constexpr int kSmallestCoverageTile = 64;

}  // namespace

std::string mebibytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return text;
}

std::vector<PixelRect> quarters(const PixelRect& tile, int block) {
    auto half = [block](int size) { return size >= 2 * block ? (size / 2 + block - 1) / block * block : size; };
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

FramePlan planFrame(const FrameFacts& facts, const RenderSettings& settings) {
    FramePlan plan;
    // A union of leaves seen from outside is drawn plainly (PlainPass.h),
    // except where a frame asks for what only the peel has: the layers, the
    // evaluator's forms, or the result's later surfaces.
    plan.plainFrame = settings.plainUnions && facts.outside && facts.plainScene && !facts.resultPeel &&
                      !settings.keepPeelLayers && !settings.keepBlockForms;
    // Debug views show each operand's own layers: no groups there. Unions
    // group where every ray starts outside, as the first layer does
    // (Renderer's peelAndEvaluate), and not for the result peel, which
    // walks past it.
    const bool unions = facts.outside && !facts.resultPeel &&
                        facts.unionOnlyOperands >= static_cast<std::size_t>(std::max(settings.unionGroupFrom, 2));
    // Where the root is a union of plain leaves and of more, those leaves
    // are drawn plainly and the rest evaluated after them, in the frames a
    // plain frame would take.
    plan.plainBeside = !plan.plainFrame && settings.plainUnions && facts.outside && facts.plainBesideScene &&
                       facts.plainBesideShare >= settings.plainBesideFrom && !facts.resultPeel &&
                       !settings.keepPeelLayers && !settings.keepBlockForms;
    const bool grouping = settings.groupOperands && !settings.keepPeelLayers;
    plan.form = plan.plainBeside ? (grouping ? TreeForm::BesidePlainGrouped : TreeForm::BesidePlainSeparate)
                : !grouping      ? TreeForm::Separate
                : unions         ? TreeForm::UnionGrouped
                                 : TreeForm::Grouped;
    // A plain frame only shown (nothing read back) writes what the image
    // and the passes after it need and nothing else, and clears that itself
    // (PlainPass::Output::shownOnly).
    plan.shownOnly = plan.plainFrame && !facts.aovs;
    plan.evaluated = !plan.plainFrame &&
                     facts.kinds[static_cast<std::size_t>(plan.form)] == csg::CompiledTree::Kind::Code;
    // A frame with no outline is lit as its surfaces are drawn: no shade
    // pass, whose outline alone needs the G-buffer around a pixel. A plain
    // frame by the plain pass (PlainPass.h), an evaluated one by the normal
    // pass (NormalPass.h), where its normals are not read back.
    plan.aovNormals = facts.aovs && settings.readNormal;
    plan.litAsDrawn =
        !settings.outline && (plan.plainFrame || (plan.evaluated && !plan.aovNormals && !facts.resultPeel));
    plan.resultPeel = facts.resultPeel;
    // Every ray starts outside every operand: those that only unions lead to
    // need their first layer alone (the debug views show every layer, and
    // the result peel walks past it).
    plan.firstLayerOnly = facts.outside && !settings.keepPeelLayers && !facts.resultPeel;
    return plan;
}

double plainBesideShare(int width, int height, int block, const std::vector<PixelRect>& plain,
                        const std::vector<PixelRect>& csg) {
    const int columns = (width + block - 1) / block, rows = (height + block - 1) / block;
    if (columns <= 0 || rows <= 0) return 0.0;
    // Bit 1: a plain leaf meets the block; bit 2: a CSG operand does.
    std::vector<unsigned char> reach(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), 0);
    auto mark = [&](const PixelRect& rect, unsigned char bit) {
        const PixelRect r = rect.intersection({0, 0, width, height});
        if (r.empty()) return;
        for (int by = r.y / block; by <= (r.y + r.height - 1) / block; ++by)
            for (int bx = r.x / block; bx <= (r.x + r.width - 1) / block; ++bx)
                reach[static_cast<std::size_t>(by) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(bx)] |= bit;
    };
    for (const PixelRect& r : plain) mark(r, 1);
    for (const PixelRect& r : csg) mark(r, 2);
    std::size_t drawn = 0, plainOnly = 0;
    for (unsigned char b : reach) {
        drawn += b != 0;
        plainOnly += b == 1;
    }
    return drawn == 0 ? 0.0 : static_cast<double>(plainOnly) / static_cast<double>(drawn);
}

TileGrid planTileGrid(int width, int height, const std::vector<PixelRect>& rects, const RenderSettings& settings,
                      int block, const std::function<TileEstimate(const std::vector<char>& inTile)>& estimate) {
    // The whole frame, or an even grid of quarters, of quarters of those,
    // ..., as fine as the densest tile needs for the layers its operands
    // need (a first guess for auto) to fit the budget. Only the operands
    // whose rectangle meets a tile are peeled for it, so memory follows the
    // operands per tile, not their number in the frame. One tile size for
    // the whole frame lets every tile (and the next frame) reuse one layer
    // texture: llvmpipe zeroes each new texture, and a fresh 512 MiB costs
    // more than the peel of several extra tiles.
    const std::size_t budget = settings.budget();
    std::vector<char> inTile(rects.size());
    auto area = [](const PixelRect& tile) {
        return static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height);
    };
    // A grid and each of its tiles' estimates, made once per grid.
    struct Grid {
        std::vector<PixelRect> tiles;
        std::vector<TileEstimate> estimates;
    };
    auto withEstimates = [&](std::vector<PixelRect> tiles) {
        Grid grid{std::move(tiles), {}};
        for (const PixelRect& tile : grid.tiles) {
            for (std::size_t k = 0; k < rects.size(); ++k) inTile[k] = rects[k].intersects(tile) ? 1 : 0;
            grid.estimates.push_back(estimate(inTile));
        }
        return grid;
    };
    auto bytes = [&](const Grid& grid, std::size_t t) { return grid.estimates[t].bytesPerPixel * area(grid.tiles[t]); };
    auto quartered = [block](const Grid& grid) {
        std::vector<PixelRect> parts;
        for (const PixelRect& tile : grid.tiles) {
            for (const PixelRect& part : quarters(tile, block)) parts.push_back(part);
        }
        return parts;
    };
    Grid grid = withEstimates({PixelRect{0, 0, width, height}});
    TileGrid plan;
    plan.wholeLayerBytes = bytes(grid, 0);
    for (;;) {
        std::size_t over = 0;
        while (over < grid.tiles.size() && bytes(grid, over) <= budget) ++over;
        if (over == grid.tiles.size()) break;
        std::vector<PixelRect> parts = quartered(grid);
        if (parts.size() == grid.tiles.size()) {  // no tile can be cut: `over` is as small as tiles get
            const TileEstimate& most = grid.estimates[over];
            const std::size_t perPixel = most.bytesPerPixel;
            throw Error("renderer: a memory budget of " + mebibytes(budget) + " holds " + std::to_string(most.layers) +
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
        for (const TileEstimate& e : g.estimates) sum += static_cast<std::size_t>(e.layers);
        return sum;
    };
    auto layerBytes = [&](const Grid& g) {
        std::size_t most = 0;
        for (std::size_t t = 0; t < g.tiles.size(); ++t) most = std::max(most, bytes(g, t));
        return most;
    };
    plan.budgetTiles = grid.tiles.size();
    while (layerBytes(grid) > settings.coverageTiling()) {
        std::vector<PixelRect> parts = quartered(grid);
        const bool small = std::any_of(parts.begin(), parts.end(), [](const PixelRect& tile) {
            return std::min(tile.width, tile.height) < kSmallestCoverageTile;
        });
        if (parts.size() == grid.tiles.size() || small) break;
        Grid cut = withEstimates(std::move(parts));
        if (static_cast<double>(draws(cut)) > settings.coverageTilingDraws * static_cast<double>(draws(grid))) break;
        grid = std::move(cut);
    }
    plan.tiles = std::move(grid.tiles);
    return plan;
}

}  // namespace strata::render
