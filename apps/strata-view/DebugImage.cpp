#include "DebugImage.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>

namespace strata::view {
namespace {

constexpr std::uint8_t kEmpty[4] = {0, 0, 0, 255};
constexpr std::uint8_t kGridBackground[4] = {40, 40, 48, 255};
constexpr int kGap = 2;  // pixels between grid tiles

struct Range {
    float lo = INFINITY, hi = -INFINITY;
    void extend(std::span<const float> depths) {
        for (float d : depths)
            if (std::isfinite(d)) {
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
    }
    // 255 at the nearest depth, 40 at the farthest, so the far end stays
    // distinct from a miss.
    std::uint8_t grey(float d) const {
        const float t = hi > lo ? (d - lo) / (hi - lo) : 0.0f;
        return static_cast<std::uint8_t>(std::lround(255.0f - 215.0f * std::clamp(t, 0.0f, 1.0f)));
    }
};

void put(std::vector<std::uint8_t>& rgba, std::size_t pixel, const std::uint8_t c[4]) {
    std::copy(c, c + 4, rgba.begin() + static_cast<std::ptrdiff_t>(pixel * 4));
}

}  // namespace

DebugImage depthImage(const render::Frame& frame) {
    DebugImage image{frame.width, frame.height, std::vector<std::uint8_t>(frame.depth.size() * 4)};
    Range range;
    range.extend(frame.depth);
    for (std::size_t k = 0; k < frame.depth.size(); ++k) {
        const float d = frame.depth[k];
        if (!std::isfinite(d)) {
            put(image.rgba, k, kEmpty);
            continue;
        }
        const std::uint8_t g = range.grey(d);
        const std::uint8_t c[4] = {g, g, g, 255};
        put(image.rgba, k, c);
    }
    return image;
}

DebugImage formsImage(const render::Frame& frame) {
    DebugImage image{frame.width, frame.height, frame.rgba};
    for (std::size_t k = 0; k < frame.blockForms.size() && k * 4 < image.rgba.size(); ++k) {
        const auto form = static_cast<std::size_t>(frame.blockForms[k]);
        for (std::size_t c = 0; c < 3; ++c) {
            std::uint8_t& v = image.rgba[k * 4 + c];
            v = static_cast<std::uint8_t>(form == 0 ? v / 3 : (v + kFormColors[form][c]) / 2);
        }
    }
    return image;
}

DebugImage normalImage(const render::Frame& frame) {
    DebugImage image{frame.width, frame.height, std::vector<std::uint8_t>(frame.normal.size() * 4)};
    for (std::size_t k = 0; k < frame.normal.size(); ++k) {
        const glm::vec3 n = frame.normal[k];
        if (n == glm::vec3(0.0f)) {
            put(image.rgba, k, kEmpty);
            continue;
        }
        std::uint8_t c[4] = {0, 0, 0, 255};
        for (int a = 0; a < 3; ++a)
            c[a] = static_cast<std::uint8_t>(std::lround(std::clamp((n[a] + 1.0f) * 0.5f, 0.0f, 1.0f) * 255.0f));
        put(image.rgba, k, c);
    }
    return image;
}

PeelGrid peelGrid(const render::Frame& frame, int width, int height) {
    PeelGrid grid;
    grid.image = DebugImage{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
    for (std::size_t k = 0; k < grid.image.rgba.size() / 4; ++k) put(grid.image.rgba, k, kGridBackground);
    if (frame.peelLayers.empty() || frame.width <= 0 || frame.height <= 0) return grid;

    std::map<int, int> blockOfLeaf;  // operands in the order the frame lists them
    int layers = 0;
    Range range;
    for (const render::PeelLayerImage& layer : frame.peelLayers) {
        blockOfLeaf.try_emplace(layer.leaf, static_cast<int>(blockOfLeaf.size()));
        layers = std::max(layers, layer.layer + 1);
        range.extend(layer.nearDepth);
        range.extend(layer.farDepth);
    }
    // Each operand is a block of 2 * layers tiles in a row; blocks wrap into
    // as many block columns as give the largest tiles of the frame's shape.
    const int operands = static_cast<int>(blockOfLeaf.size());
    double scale = 0.0;
    int blockColumns = 1;
    for (int c = 1; c <= operands; ++c) {
        const int columns = 2 * layers * c, rows = (operands + c - 1) / c;
        const double s = std::min((width - kGap * (columns + 1)) / double(columns * frame.width),
                                  (height - kGap * (rows + 1)) / double(rows * frame.height));
        if (s > scale) {
            scale = s;
            blockColumns = c;
        }
    }
    const int tw = static_cast<int>(frame.width * scale), th = static_cast<int>(frame.height * scale);
    if (tw < 1 || th < 1) return grid;

    for (const render::PeelLayerImage& layer : frame.peelLayers) {
        for (int side = 0; side < 2; ++side) {
            PeelTile tile{layer.leaf, layer.layer, side == 1, 0, 0, tw, th};
            const int block = blockOfLeaf[layer.leaf];
            tile.x = kGap + ((block % blockColumns) * 2 * layers + 2 * layer.layer + side) * (tw + kGap);
            tile.y = kGap + (block / blockColumns) * (th + kGap);
            const std::vector<float>& depth = side == 0 ? layer.nearDepth : layer.farDepth;
            for (int y = 0; y < th; ++y) {
                const int sy = std::min(frame.height - 1, static_cast<int>((y + 0.5) / scale));
                for (int x = 0; x < tw; ++x) {
                    const int sx = std::min(frame.width - 1, static_cast<int>((x + 0.5) / scale));
                    const float d = depth[static_cast<std::size_t>(sy) * frame.width + sx];
                    const std::uint8_t g = std::isfinite(d) ? range.grey(d) : 0;
                    const std::uint8_t c[4] = {g, g, g, 255};
                    put(grid.image.rgba, static_cast<std::size_t>(tile.y + y) * width + (tile.x + x), c);
                }
            }
            grid.tiles.push_back(tile);
        }
    }
    return grid;
}

}  // namespace strata::view
