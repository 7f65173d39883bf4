#pragma once
// The translucent pass: '%' (background) and '#' (highlight) leaves drawn
// alpha-blended over the shaded image, front faces only, hidden behind the
// result's visible surface (shaders/csg/translucent.frag). Colours follow
// OpenSCAD: highlight is always its pink, background a leaf's color() or grey.
//
// GL state: enables blending and back-face culling while it runs, disables
// both before returning; viewport = the frame.

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
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view,
             const std::vector<TranslucentLeaf>& leaves);

private:
    gpu::Program program_;
};

}  // namespace strata::render
