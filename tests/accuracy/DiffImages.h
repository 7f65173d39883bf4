#pragma once
// Pictures of a comparison: the two AOV images in one false-colour shading
// (so strata and the reference look alike where they agree), the diff heat
// map, and the three side by side. Written as 8-bit RGBA PNG (strata::io).
//
// False colour: a hue per leaf id, brightness from the normal against the
// view ray; misses are a dark grey.
// Heat map: agreeing pixels are the reference image, dimmed (edge pixels
// tinted blue); disagreements are
//   red      coverage (one path sees a surface, the other none)
//   yellow   depth (orange at the tolerance to yellow at 1000x it)
//   cyan     normal
//   green    leaf id
//   magenta  cut bit (the face colour against the cut-face colour)
// at full strength off edges, at half strength on edge pixels.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "Compare.h"

namespace strata::accuracy {

struct RgbaImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // W*H*4, row 0 at the top
};

RgbaImage falseColour(const camera::Camera& camera, const AovView& image);
RgbaImage heatMap(const camera::Camera& camera, const AovView& gpu, const AovView& reference,
                  const CompareResult& result);
// The images left to right with `gap` pixels of white between, top-aligned.
RgbaImage sideBySide(std::span<const RgbaImage> images, int gap = 2);

void writePng(const std::string& path, const RgbaImage& image);

struct ComparisonImages {
    std::string gpu, reference, diff, strip;  // paths written
};

// Writes <prefix>-strata.png, <prefix>-reference.png, <prefix>-diff.png and
// <prefix>-strip.png (the three side by side), creating prefix's folder.
ComparisonImages writeComparisonImages(const std::string& prefix, const camera::Camera& camera, const AovView& gpu,
                                       const AovView& reference, const CompareResult& result);

}  // namespace strata::accuracy
