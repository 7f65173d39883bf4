#pragma once
// The lines strata-view draws over the CSG image in its own pass, into the
// view's colour target after strata's image is in it: OpenSCAD's axes and
// scale markers with their numbers, its small axis cross in the lower-left
// corner, and "show edges". The axes and edges are tested against the
// frame's depth and leaf AOVs (shaders/view/overlay.frag), so a frame with
// any of them on is rendered with Renderer::render (read back) instead of
// renderInto; so are the debug views they are drawn over.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"

namespace strata::view {

struct OverlayOptions {
    bool axes = false;     // axes, and the axis cross in the corner (OpenSCAD: View > Show Axes)
    bool scale = false;    // scale markers and their numbers, with axes only (View > Show Scale Markers)
    bool edges = false;    // the visible surfaces' triangle edges (View > Show Edges)
    glm::vec3 axesColor{0.0f};

    bool any() const { return axes || edges; }
};

class Overlay {
public:
    Overlay();  // needs a current GL context
    // The leaves' edges, kept for every frame until the next scene.
    void setScene(const model::Model& model);
    // Draws into `framebuffer` (camera.width x camera.height), over `image`
    // (RGBA8, row 0 at the top: the frame's own, or a debug view's), which
    // is already in it; tested against the frame's depth and leaf AOVs.
    void draw(unsigned framebuffer, const camera::Camera& camera, const render::Frame& frame,
              const std::vector<std::uint8_t>& image, const OverlayOptions& options);

private:
    gpu::Program program_;
    gpu::VertexArray edgeArray_, lineArray_;
    gpu::Buffer edgeVertices_, lineVertices_;
    std::size_t edgeCount_ = 0;  // vertices
    gpu::Texture depth_, leaf_, color_;
};

}  // namespace strata::view
