#pragma once
// The translucent pass: '%' (background) and '#' (highlight) leaves drawn
// alpha-blended over the shaded image, front faces only, hidden behind the
// result's visible surface (shaders/csg/translucent.frag). Colours follow
// OpenSCAD: highlight is always its pink, background a leaf's color() or grey.
//
// GL state: enables blending and back-face culling while it runs, disables
// both before returning; viewport = the frame.

#include <optional>
#include <vector>

#include <glm/vec4.hpp>

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/gpu/Program.h"

namespace strata::render {

struct TranslucentLeaf {
    int leaf = 0;
    glm::vec4 color{1.0f};  // straight alpha
};

class TranslucentPass {
public:
    TranslucentPass();
    // The result's depth is targets.resultDepth, or, where `windowDepth` is
    // given, that image of a plain frame only shown (PlainPass.h): its
    // reversed window depth, which `view` turns back into view depths.
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
             const std::vector<TranslucentLeaf>& leaves, const gpu::Texture* windowDepth = nullptr);

private:
    // Compiled at first use: [1] the WINDOW_DEPTH variant.
    gpu::Program& program(bool windowDepth);
    std::optional<gpu::Program> programs_[2];
};

}  // namespace strata::render
