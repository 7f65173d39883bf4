#pragma once
// The floor the bench compares against: every CSG leaf's triangles drawn
// once into a framebuffer of the frame's size with a GL_LESS depth test and
// no culling (shaders/bench/plain.*). No CSG at all: what any renderer must
// pay to rasterize the scene once.

#include <cstddef>

#include "strata/camera/Camera.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::bench {

class PlainDraw {
public:
    // Uploads the meshes of the leaves in the CSG (background leaves left
    // out) as one array of world-space float positions. Needs a current context.
    PlainDraw(const scene::Tree& tree, const model::Model& model, int width, int height);

    // Clears, draws everything, glFinish. Returns wall-clock milliseconds.
    double drawFrame(const camera::Camera& camera);

    std::size_t triangles() const noexcept { return vertices_ / 3; }

private:
    gpu::Program program_;
    gpu::Buffer positions_;
    gpu::VertexArray vertexArray_;
    gpu::Texture color_;
    gpu::Texture depth_;
    gpu::Framebuffer framebuffer_;
    mesh::Bounds bounds_;
    std::size_t vertices_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace strata::bench
