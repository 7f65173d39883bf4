#pragma once
// The shade pass (deferred): one fullscreen draw that turns the G-buffer into
// the colour image (shaders/csg/shade.frag): each pixel's base colour (leaf or
// scheme colour, which the normal pass stores beside the normal), lit by
// strata's light or OpenSCAD's (Lighting), a Sobel outline on the normals
// where asked, the scheme's background on empty pixels.
//
// GL state: viewport = the frame; leaves the stencil test off; expects
// blending, depth test, culling and the scissor test off.

#include <array>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

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
    // With `marked`: clear to the background and shade only the pixels the
    // evaluator or the plain path marked (FrameTargets::shadeTarget's
    // stencil), all of which lie inside that
    // rectangle; the marks outside it are not read. Without: shade every
    // pixel (a G-buffer that came from elsewhere has no marks).
    void run(FrameTargets& targets, const ViewSetup& view, const ColorScheme& scheme, Lighting lighting,
             bool outline, const std::optional<PixelRect>& marked);

    // OpenSCAD's light (Lighting::OpenScad) in world space: the unit
    // direction (-1, 1, 1) of view space, x right, y up, z towards the eye.
    static glm::vec3 openScadToLight(const ViewSetup& view);
    // Sets light.glsl's uniforms in `program`, one built for `lighting`
    // (OPENSCAD_LIGHT defined for Lighting::OpenScad) that includes it.
    static void setLight(gpu::Program& program, const ViewSetup& view, Lighting lighting);

    // A base colour as the G-buffer carries it (FrameTargets::normal's w):
    // 1 + its 8-bit RGB as the integer r * 65536 + g * 256 + b, exact in a
    // float; 0 means no surface. The shader unpacks it, so the per-pixel
    // colour costs no lookup by leaf.
    static float packBaseColor(const glm::vec3& rgb);
    // Per tree leaf, packed: x where the result shows the leaf's own surface
    // (its color(), else the scheme's face colour), y where the leaf is cut
    // (its color(), else the scheme's cut-face colour).
    static std::vector<glm::vec2> baseColors(const SceneBuffers& scene, const ColorScheme& scheme);

private:
    // One program per light and outline, each compiled at its first use.
    std::array<std::optional<gpu::Program>, 4> programs_;
    gpu::VertexArray empty_;
};

}  // namespace strata::render
