#pragma once
// The shade pass (deferred): one fullscreen draw that turns the G-buffer into
// the colour image (shaders/csg/shade.frag): leaf or scheme colours, Lambert
// light from beside the eye plus ambient, a Sobel outline on the normals, the
// scheme's background on empty pixels.
//
// GL state: viewport = the frame; leaves the stencil test off; expects
// blending, depth test, culling and the scissor test off.

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/ColorScheme.h"

namespace strata::render {

class ShadePass {
public:
    ShadePass();
    // markedOnly: clear to the background and shade only the pixels the
    // evaluator marked (FrameTargets::marks); otherwise shade every pixel (a
    // G-buffer that came from elsewhere has no marks).
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const ColorScheme& scheme,
             bool markedOnly);

private:
    gpu::Program program_;
    gpu::VertexArray empty_;
};

}  // namespace strata::render
