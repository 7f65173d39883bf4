#pragma once
// The view and projection every non-strata draw of the bench uses (the plain
// floor and OpenCSG), so both rasterize the same triangles to the same depths.

#include <glm/mat4x4.hpp>

#include "strata/camera/Camera.h"
#include "strata/mesh/Mesh.h"

namespace strata::bench {

struct ViewMatrices {
    glm::dmat4 view{1.0};
    glm::dmat4 projection{1.0};
};

// The camera's view and projection with near and far planes hugging `bounds`
// (what the camera sees of the drawn triangles), as a viewer would set them.
ViewMatrices fittedView(const camera::Camera& camera, const mesh::Bounds& bounds);

}  // namespace strata::bench
