#include "PlainDraw.h"

#include <chrono>
#include <vector>

#include <glm/vec3.hpp>

#include "ViewMatrices.h"
#include "strata/core/Timing.h"
#include "strata/gpu/Check.h"

namespace strata::bench {

PlainDraw::PlainDraw(const scene::Tree& tree, const model::Model& model, int width, int height)
    : program_(gpu::Program::fromFiles("bench plain", {"bench/plain.vert", "bench/plain.frag"})),
      vertexArray_("bench plain"),
      color_(gpu::Texture::create2D("bench plain color", GL_RGBA8, width, height)),
      depth_(gpu::Texture::create2D("bench plain depth", GL_DEPTH_COMPONENT32F, width, height)),
      framebuffer_("bench plain"),
      width_(width),
      height_(height) {
    std::vector<bool> inCsg(tree.leaves.size(), false);
    for (int l : tree.leavesUnder(tree.root)) inCsg[static_cast<std::size_t>(l)] = true;

    std::vector<glm::vec3> positions;
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        if (!inCsg[i]) continue;
        const mesh::Mesh& mesh = model.leafMeshes[i];
        for (const auto& tri : mesh.triangles)
            for (std::uint32_t v : tri) {
                positions.emplace_back(mesh.positions[v]);
                bounds_.extend(mesh.positions[v]);
            }
    }
    vertices_ = positions.size();
    positions_ = gpu::Buffer::fromSpan<glm::vec3>("bench plain positions", positions, 0);
    vertexArray_.setVertexBuffer(0, positions_, 0, sizeof(glm::vec3));
    vertexArray_.setAttribute(0, 0, 3, GL_FLOAT, 0);

    framebuffer_.attachTexture(GL_COLOR_ATTACHMENT0, color_);
    framebuffer_.attachTexture(GL_DEPTH_ATTACHMENT, depth_);
    framebuffer_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    framebuffer_.checkComplete();
    gpu::checkErrors();
}

double PlainDraw::drawFrame(const camera::Camera& camera) {
    const ViewMatrices matrices = fittedView(camera, bounds_);
    const glm::mat4 viewProjection(matrices.projection * matrices.view);
    program_.setUniform("viewProjection", viewProjection);

    const auto start = std::chrono::steady_clock::now();
    framebuffer_.bindForDraw();
    glViewport(0, 0, width_, height_);
    const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    framebuffer_.clearColor(0, background);
    framebuffer_.clearDepth(1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    program_.use();
    vertexArray_.bind();
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_));
    glFinish();
    const double ms = msSince(start);
    glDisable(GL_DEPTH_TEST);
    gpu::checkErrors();
    return ms;
}

}  // namespace strata::bench
