#pragma once
// The normal pass: recovers the world-space outward normal of the evaluated
// result. The leaves that the evaluator chose somewhere in a tile are drawn
// once more, each clipped to the pixels that show it; the fragment whose leaf,
// facing and tagged depth match the evaluator's choice writes its triangle's
// face normal (SceneBuffers::faceNormals through gl_PrimitiveID), negated
// where the leaf acts as a subtracted operand. One more geometry pass over
// the visible leaves instead of storing ids with every peeled layer.
//
// It draws with the peel pass's exact viewport (into a tile-sized scratch
// image, then copied into FrameTargets::normal), so the depths it computes
// match the peeled ones bit for bit.
//
// GL state: enables the scissor test while it runs and disables it before
// returning; expects blending, depth test and culling off.

#include <vector>

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"

namespace strata::render {

struct LeafPixels {
    int leaf = 0;
    PixelRect rect;  // tile-relative pixels where the result shows this leaf
};

class NormalPass {
public:
    NormalPass();

    // The leaves the result shows in `tile`, read back from
    // FrameTargets::resultLeaf, each with the rectangle of its pixels.
    static std::vector<LeafPixels> visibleLeaves(const FrameTargets& targets, const PixelRect& tile);

    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& tile,
             const std::vector<LeafPixels>& leaves);

private:
    gpu::Program program_;
    gpu::Texture scratch_;
    gpu::Framebuffer target_;
};

}  // namespace strata::render
