#pragma once
// The image-space CSG renderer: peel every operand into layers, evaluate the
// tree per pixel, shade the first visible surface. Needs a current OpenGL 4.5
// core context (strata::gpu) on the calling thread for its whole life.
//
// The passes (engine/render/*Pass.h, shaders/csg/) and what each owns:
//   peel       PeelPass        dual depth peeling into an RG32F array texture
//   evaluate   EvaluatePass    the compiled tree (strata/csg/CompiledTree.h) per pixel
//   normal     NormalPass      the visible leaves redrawn for face normals
//   plain      PlainPass       in place of those three for a union seen from
//                              outside: its front faces depth-tested into the G-buffer
//   shade      ShadePass       colours, light, Sobel outline
//   translucent TranslucentPass '%' and '#' leaves over the image
// GL state on return: depth test, stencil test, culling, blending and scissor test off;
// the viewport, bound program, vertex array, textures, storage buffers and
// draw framebuffer are whatever the last pass used (renderInto: the host's).

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/model/Model.h"
#include "strata/render/Frame.h"
#include "strata/scene/Tree.h"

namespace strata::render {

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads the leaf meshes and compiles the tree (the passes' shaders are
    // compiled by the first frame that needs them). Call again after an edit.
    void setScene(const scene::Tree& tree, const model::Model& model);
    // The same, letting each leaf's mesh go as soon as it is on the GPU and
    // handing the memory back: for a caller that needs the meshes no more
    // (a million cubes then peak about 400 MB lower). `model` is left empty.
    void setScene(const scene::Tree& tree, model::Model&& model);

    // `settings` with what it leaves unset (RenderSettings::memoryBudget,
    // ::coverageTilingFrom) filled in as this renderer's GL device wants
    // them; every frame takes its settings so.
    RenderSettings deviceSettings(const RenderSettings& settings) const;

    // Renders and reads everything back.
    Frame render(const camera::Camera& camera, const RenderSettings& settings);

    // Renders without reading anything back, and copies the shaded image into
    // the host's `framebuffer` (a GL framebuffer name; 0 is the default one)
    // with its lower-left corner at (x, y) in that framebuffer's pixels: for a
    // window or a host's own render target. Returns the frame's figures
    // (readbackMs covers the copy; coveredPixels is not counted).
    // Leaves that framebuffer bound for drawing.
    FrameStats renderInto(unsigned framebuffer, int x, int y, const camera::Camera& camera, const RenderSettings& settings);

    // Every place along each pixel's ray where the result's membership
    // changes, front to back, by peeling the result: each tile's operands are
    // peeled once (every layer), then each round evaluates the tree again,
    // walking on from the change the round before found, until no ray of the
    // tile has one more. `onRound` gets each tile's rounds in order; a ray
    // whose changes end in one round has +inf in the rounds after. The rays
    // start at the near plane: for every change to show, the camera should
    // see the whole model from outside it (the export's orthographic views).
    // Nothing is shaded. Returns the figures (coveredPixels: changes found).
    FrameStats sampleResult(const camera::Camera& camera, const RenderSettings& settings,
                            const std::function<void(const ResultRound&)>& onRound);

    // Shades a result computed elsewhere (the CPU reference of strata-render
    // --reference) with the same shade and translucent passes as render(), and
    // reads it back like render(). Every span holds camera.width * camera.height
    // values, rows top first as in Frame; `cut` is 1 where the leaf acts as a
    // subtracted operand. The returned Frame carries these AOVs unchanged.
    struct ExternalResult {
        std::span<const float> depth;
        std::span<const glm::vec3> normal;
        std::span<const std::int32_t> leaf;
        std::span<const std::uint8_t> cut;
    };
    Frame shade(const camera::Camera& camera, const RenderSettings& settings, const ExternalResult& result);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strata::render
