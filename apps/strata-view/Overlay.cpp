#include "Overlay.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "OverlayLines.h"
#include "strata/gpu/Gl.h"

namespace strata::view {
namespace {

// The line kinds of shaders/view/overlay.vert besides an edge's leaf.
constexpr float kSolid = -1.0f, kDashed = -2.0f;

struct Vertex {
    glm::vec3 position;
    glm::vec3 color;
    float kind;
};

void describe(gpu::VertexArray& array, const gpu::Buffer& buffer) {
    array.setVertexBuffer(0, buffer, 0, sizeof(Vertex));
    array.setAttribute(0, 0, 3, GL_FLOAT, offsetof(Vertex, position));
    array.setAttribute(1, 0, 3, GL_FLOAT, offsetof(Vertex, color));
    array.setAttribute(2, 0, 1, GL_FLOAT, offsetof(Vertex, kind));
}

void upload(gpu::Buffer& buffer, gpu::VertexArray& array, const char* label, const std::vector<Vertex>& vertices) {
    buffer = gpu::Buffer::fromSpan<Vertex>(label, vertices, 0);
    describe(array, buffer);
}

}  // namespace

Overlay::Overlay()
    : program_(gpu::Program::fromFiles("strata-view overlay", {"view/overlay.vert", "view/overlay.frag"})),
      edgeArray_("strata-view edges"),
      lineArray_("strata-view lines") {}

void Overlay::setScene(const model::Model& model) {
    std::vector<Vertex> vertices;
    std::vector<glm::vec3> points;
    for (std::size_t leaf = 0; leaf < model.leafMeshes.size(); ++leaf) {
        points.clear();
        appendMeshEdges(model.leafMeshes[leaf], points);
        for (const glm::vec3& p : points) vertices.push_back({p, glm::vec3(0.5f), static_cast<float>(leaf)});
    }
    edgeCount_ = vertices.size();
    edgeVertices_ = gpu::Buffer();
    edgeArray_ = gpu::VertexArray("strata-view edges");
    if (!vertices.empty()) upload(edgeVertices_, edgeArray_, "strata-view edges", vertices);
}

void Overlay::draw(unsigned framebuffer, const camera::Camera& camera, const render::Frame& frame,
                   const std::vector<std::uint8_t>& image, const OverlayOptions& options) {
    const int w = camera.width, h = camera.height;
    if (depth_.id() == 0 || depth_.width() != w || depth_.height() != h) {
        depth_ = gpu::Texture::create2D("strata-view overlay depth", GL_R32F, w, h);
        leaf_ = gpu::Texture::create2D("strata-view overlay leaf", GL_R32I, w, h);
        color_ = gpu::Texture::create2D("strata-view overlay image", GL_RGBA8, w, h);
        for (const gpu::Texture* t : {&depth_, &leaf_, &color_}) {
            glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    depth_.upload(0, 0, 0, w, h, 1, GL_RED, GL_FLOAT, frame.depth.data());
    leaf_.upload(0, 0, 0, w, h, 1, GL_RED_INTEGER, GL_INT, frame.leaf.data());
    color_.upload(0, 0, 0, w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE, image.data());

    const double d = glm::length(camera.eye - camera.center);
    const bool ortho = camera.projection == camera::Projection::Orthographic;
    // Wide enough for the axes (the distance either side of the origin) and the scene.
    const glm::dmat4 viewProjection = camera.projectionMatrix(ortho ? -1e4 * d : 1e-3 * d, 1e4 * d) * camera.viewMatrix();
    const glm::dvec4 origin = viewProjection * glm::dvec4(0, 0, 0, 1);
    const glm::vec2 originPixel = origin.w > 0.0 ? glm::vec2((origin.x / origin.w + 1.0) * 0.5 * w,
                                                             (origin.y / origin.w + 1.0) * 0.5 * h)
                                                 : glm::vec2(-1e6f);
    // A pixel's width in world units at view depth z.
    const double halfHeightPerDepth = std::tan(camera.fovDegrees * 3.14159265358979323846 / 360.0);
    const glm::vec2 footprint = ortho ? glm::vec2(2.0 * d * halfHeightPerDepth / h, 0.0)
                                      : glm::vec2(0.0, 2.0 * halfHeightPerDepth / h);

    program_.setUniform("viewProjection", glm::mat4(viewProjection));
    program_.setUniform("eye", glm::vec3(camera.eye));
    program_.setUniform("forward", glm::vec3(camera.forward()));
    program_.setUniform("viewSize", glm::vec2(w, h));
    program_.setUniform("viewHeight", h);
    program_.setUniform("originPixel", originPixel);
    program_.setUniform("footprint", footprint);
    program_.setUniform("sceneDepth", 0);
    program_.setUniform("sceneLeaf", 1);
    program_.setUniform("sceneColor", 2);
    program_.setUniform("screenSpace", 0);
    depth_.bindUnit(0);
    leaf_.bindUnit(1);
    color_.bindUnit(2);

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glLineWidth(1.0f);
    program_.use();

    if (options.edges && edgeCount_ > 0) {
        // (1 + surface) / 2 with the shader's (0.5, 0.5, 0.5, 0.5); its colour
        // alone with alpha 0 (outside a silhouette). The image's alpha is kept.
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
        edgeArray_.bind();
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(edgeCount_));
        glDisable(GL_BLEND);
    }

    if (options.axes) {
        std::vector<Vertex> world, screen;
        for (const WorldSegment& s : axisSegments(d, options.scale)) {
            const float kind = s.dashed ? kDashed : kSolid;
            world.push_back({glm::vec3(s.a), options.axesColor, kind});
            world.push_back({glm::vec3(s.b), options.axesColor, kind});
        }
        if (options.scale)
            for (const WorldSegment& s : scaleLabelSegments(d)) {
                world.push_back({glm::vec3(s.a), options.axesColor, kSolid});
                world.push_back({glm::vec3(s.b), options.axesColor, kSolid});
            }
        for (const ScreenSegment& s : gizmoSegments(camera, options.axesColor)) {
            screen.push_back({glm::vec3(s.a, 0.0), s.color, kSolid});
            screen.push_back({glm::vec3(s.b, 0.0), s.color, kSolid});
        }
        std::vector<Vertex> all = world;
        all.insert(all.end(), screen.begin(), screen.end());
        upload(lineVertices_, lineArray_, "strata-view lines", all);
        lineArray_.bind();
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(world.size()));
        program_.setUniform("screenSpace", 1);
        glDrawArrays(GL_LINES, static_cast<GLint>(world.size()), static_cast<GLsizei>(screen.size()));
    }
}

}  // namespace strata::view
