#pragma once
// The alpha pass: leaves whose color() is translucent (alpha a < 1), drawn
// as OpenSCAD 2021.01's preview draws them (docs/algorithm.md, "Translucent
// colours"). The result is the same solid as without alpha: its visible
// surface hides whatever lies behind it, and the shade pass lights it as any
// other (F). Where that surface is a translucent leaf's, this pass blends
// over F what OpenSCAD's preview shows behind it, U, with alpha 1 - a, so
// the pixel becomes a F + (1 - a) U (shaders/csg/alpha.frag):
//  - for a leaf alone in its OpenSCAD product (AlphaLeaf::alone), where the
//    result shows its own surface: its nearest back face behind that,
//    lit, over the background: U = a B + (1 - a) background;
//  - elsewhere (a leaf that meets others in an intersection or difference,
//    and a subtracted leaf's cut faces): U = the background.
//
// GL state: viewport = the frame; enables blending, the scissor test, and
// for the back faces the depth test and culling, while it runs; disables
// them before returning.

#include <array>
#include <optional>
#include <vector>

#include <glm/vec4.hpp>

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/ColorScheme.h"

namespace strata::render {

struct AlphaLeaf {
    int leaf = 0;
    glm::vec4 color{1.0f};  // its color(), straight alpha below 1
    // Alone in its OpenSCAD product (only unions lead to it from the root):
    // OpenSCAD draws its back faces, then its front faces, each blended.
    bool alone = false;
};

class AlphaPass {
public:
    AlphaPass();
    // Reads targets.resultLeaf, which must hold kLeafMiss wherever the
    // result has no surface this frame, inside each leaf's screen rectangle.
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const ColorScheme& scheme,
             Lighting lighting, const std::vector<AlphaLeaf>& leaves);

private:
    gpu::Program plain_;  // fullscreen: the background behind
    // The leaf's back faces behind, lit by each light (Lighting's order),
    // compiled at first use.
    std::array<std::optional<gpu::Program>, 2> rears_;
    gpu::VertexArray empty_;
    // The back faces' depth test: the colour image and a depth image of its size.
    gpu::Texture depth_;
    gpu::Framebuffer target_;
};

}  // namespace strata::render
