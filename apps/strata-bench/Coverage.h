#pragma once
// How far two renderers agree on which pixels the CSG result covers.
// Silhouette pixels may differ by rasterization rules, so agreement is also
// counted "away from edges": on pixels whose 3 x 3 neighbourhood has one
// coverage in both images. The covered fraction counts only pixels either
// image covers, so a small wrong region is not drowned by the background.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::bench {

struct Agreement {
    std::size_t pixels = 0, agreeing = 0;                 // all pixels
    std::size_t interiorPixels = 0, interiorAgreeing = 0; // away from either image's edges
    std::size_t interiorCovered = 0, interiorCoveredAgreeing = 0;  // of those, covered in either image
    std::size_t coveredA = 0, coveredB = 0;
    double fraction() const { return pixels ? double(agreeing) / double(pixels) : 0.0; }
    double interiorFraction() const { return interiorPixels ? double(interiorAgreeing) / double(interiorPixels) : 0.0; }
    double coveredFraction() const {
        return interiorCovered ? double(interiorCoveredAgreeing) / double(interiorCovered) : 1.0;
    }
};

// `a` and `b`: width * height values, non-zero where covered, same row order.
Agreement compareCoverage(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width,
                          int height);

}  // namespace strata::bench
