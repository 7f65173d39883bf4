#pragma once
// The image-space CSG renderer: peel every operand into layers, evaluate the
// tree per pixel, shade the first visible surface. Needs a current OpenGL 4.5
// core context (strata::gpu) on the calling thread for its whole life.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/geometry/Model.h"
#include "strata/render/Camera.h"
#include "strata/scene/Tree.h"

namespace strata::render {

struct RenderSettings {
    int layers = 0;                            // dual-peel passes per operand; 0 = auto (until a pass draws nothing)
    std::string colorScheme = "Cornfield";     // OpenSCAD colour scheme name
    std::size_t memoryBudget = std::size_t(1) << 30;  // bytes of layered textures before tiling/batching
};

struct FrameStats {
    double peelMs = 0, evaluateMs = 0, shadeMs = 0, readbackMs = 0, totalMs = 0;
    std::vector<int> layersPerLeaf;            // peel passes used, per tree leaf (0 for leaves not drawn)
    std::size_t textureBytes = 0;              // layered-texture memory in use
    int operands = 0;                          // leaves in the CSG product
    std::size_t coveredPixels = 0;             // pixels where the result has a surface
    int tiles = 1;                             // screen tiles / operand batches used to stay in budget
    std::vector<std::string> notes;            // what the renderer decided (tiling, clamping, ...)
};

// One rendered frame, read back. Row 0 is the TOP row (as in image files).
struct Frame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;   // W*H*4, shaded image
    std::vector<float> depth;         // W*H, view depth dot(P - eye, f); +inf on miss
    std::vector<glm::vec3> normal;    // W*H, world-space unit outward normal of the result; 0 on miss
    std::vector<std::int32_t> leaf;   // W*H, tree leaf index of the visible surface; -1 on miss
    FrameStats stats;
};

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads the leaf meshes and compiles the tree. Call again after an edit.
    void setScene(const scene::Tree& tree, const geometry::Model& model);

    // Renders and reads everything back.
    Frame render(const Camera& camera, const RenderSettings& settings);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strata::render
