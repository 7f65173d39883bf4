#include "Coverage.h"

#include <algorithm>

#include "strata/core/Error.h"

namespace strata::bench {
namespace {

// True where the pixel's 3 x 3 neighbourhood (clipped to the image) is not all one coverage.
std::vector<bool> edges(const std::vector<std::uint8_t>& covered, int width, int height) {
    std::vector<bool> out(covered.size(), false);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool self = covered[std::size_t(y) * std::size_t(width) + std::size_t(x)] != 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
                    if ((covered[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] != 0) != self)
                        out[std::size_t(y) * std::size_t(width) + std::size_t(x)] = true;
                }
        }
    return out;
}

}  // namespace

Agreement compareCoverage(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width,
                          int height) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    if (a.size() != n || b.size() != n) throw Error("compareCoverage: images are not width x height");
    const std::vector<bool> edgeA = edges(a, width, height), edgeB = edges(b, width, height);
    Agreement out;
    out.pixels = n;
    for (std::size_t i = 0; i < n; ++i) {
        const bool same = (a[i] != 0) == (b[i] != 0);
        out.agreeing += same;
        out.coveredA += a[i] != 0;
        out.coveredB += b[i] != 0;
        if (edgeA[i] || edgeB[i]) continue;
        ++out.interiorPixels;
        out.interiorAgreeing += same;
        if (a[i] == 0 && b[i] == 0) continue;
        ++out.interiorCovered;
        out.interiorCoveredAgreeing += same;
    }
    return out;
}

}  // namespace strata::bench
