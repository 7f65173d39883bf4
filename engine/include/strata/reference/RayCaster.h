#pragma once
// The CPU reference: ray casting of the CSG tree on Embree 3, the accuracy
// oracle that the GPU path is compared with pixel by pixel.
//
// For each primary ray of the contract's camera it finds every crossing of
// the ray with every leaf (IntervalCsg.h turns them into interval lists and
// evaluates the tree), then reports the first point after the ray start where
// membership in the CSG result changes (docs/architecture.md, "Visible surface semantics"):
//  - a ray that starts outside the result sees where the result begins;
//  - a ray that starts inside it (the eye, or the near plane, inside the
//    model) sees where it first leaves it, with the result's outward normal
//    there. So a near plane through a solid shows what lies behind the cut,
//    not the cut itself, as the GPU path draws it.
// A leaf is inside at the ray start when an odd number of its crossings lie
// after the start.
//
// Embree finds the candidates: each leaf is one user geometry (geomID = leaf
// index) whose primitives are its triangles' boxes, padded; the callback runs
// RayTriangle.h's exact test in double precision and records the crossing
// without ending the ray, so traversal visits every triangle on it.
//
// Output is deterministic: each pixel depends only on its own ray.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::reference {

// One ray's answer.
struct RayHit {
    double t = 0.0;           // ray parameter (unit direction); +infinity on a miss
    glm::dvec3 normal{0.0};   // world-space unit outward normal of the result; 0 on a miss
    int leaf = -1;            // tree leaf whose surface it is; -1 on a miss
    bool cut = false;         // the leaf acts as a subtracted operand here (its normal is negated)
    bool hit() const { return leaf >= 0; }
};

// Same layout as render::Frame's AOVs. Row 0 is the TOP row; index j*width + i.
struct ReferenceImage {
    int width = 0;
    int height = 0;
    std::vector<float> depth;        // view depth dot(P - eye, f); +infinity on a miss
    std::vector<glm::vec3> normal;   // world-space unit outward normal; 0,0,0 on a miss
    std::vector<int> leaf;           // tree leaf index; -1 on a miss
    std::vector<std::uint8_t> cut;   // 1 where the leaf acts as a subtracted operand (a cut face)
};

struct ReferenceOptions {
    int threads = 0;          // worker threads; 0: every core
    // Rays start at this view depth instead of at the contract's ray origin
    // (depth 0), as a GPU near plane would cut them. Must be >= 0.
    double nearDepth = 0.0;
    // Crossings within the camera's coincidence tolerance count as one place
    // (docs/algorithm.md), as on the GPU; false: only equal ones, every wall
    // however thin kept (an exact mesh's image to hold others against).
    bool coincidence = true;
    // Called after each finished row with (rows done, rows), never from two
    // threads at once. May be empty.
    std::function<void(int done, int total)> progress;
};

// A progress callback that writes "label: NN%" lines on stderr, every 10%,
// once the render has run for a second (short renders stay quiet).
std::function<void(int done, int total)> progressOnStderr(const char* label = "reference");

// The scene prepared for ray casting: Embree's hierarchy over the leaves that
// take part in the CSG result. Immutable after construction; trace() and
// render() may run on several threads at once.
class ReferenceScene {
public:
    // model.leafMeshes[i] is tree.leaves[i] in world space (model::buildModel).
    // Throws strata::Error when they do not match or Embree fails.
    ReferenceScene(const scene::Tree& tree, const model::Model& model);
    ~ReferenceScene();
    ReferenceScene(ReferenceScene&&) noexcept;
    ReferenceScene& operator=(ReferenceScene&&) noexcept;

    // The first change of the result along the ray at parameter t > tStart,
    // crossings within `coincidence` (of t) counting as one place
    // (docs/algorithm.md, "Coincident surfaces"; render() takes the
    // camera's coincidenceTolerance). 0: only equal t coincide.
    RayHit trace(const camera::Ray& ray, double tStart = 0.0, double coincidence = 0.0) const;

    ReferenceImage render(const camera::Camera& camera, const ReferenceOptions& options = {}) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// ReferenceScene(tree, model).render(camera, options).
ReferenceImage renderReference(const scene::Tree& tree, const model::Model& model, const camera::Camera& camera,
                               const ReferenceOptions& options = {});

}  // namespace strata::reference
