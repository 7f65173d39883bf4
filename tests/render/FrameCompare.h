#pragma once
// Bit-for-bit comparison of two rendered frames' AOVs, for the render tests
// that check one path of the renderer against another.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstring>

#include <glm/vec3.hpp>

#include "strata/render/Renderer.h"

namespace strata::test {

// Pixels whose leaf, depth or normal differ by any bit between two frames of one size.
inline std::size_t pixelsDiffering(const render::Frame& a, const render::Frame& b) {
    EXPECT_EQ(a.leaf.size(), b.leaf.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < std::min(a.leaf.size(), b.leaf.size()); ++k) {
        differ += a.leaf[k] != b.leaf[k] || std::memcmp(&a.depth[k], &b.depth[k], sizeof(float)) != 0 ||
                  std::memcmp(&a.normal[k], &b.normal[k], sizeof(glm::vec3)) != 0;
    }
    return differ;
}

}  // namespace strata::test
