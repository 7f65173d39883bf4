#pragma once
// The CSG result as a mesh, from the image-space engine: the result sampled
// along three axes (a tri-dexel image, strata/contour/Dexels.h), then
// contoured (strata/contour/Contour.h) into a closed mesh that keeps sharp
// edges and corners (docs/algorithm.md, "Exporting the result").
//
// Two samplers fill the same image: the GPU's result peel
// (render::Renderer::sampleResult, orthographic views along +x, +y, +z, one
// pixel per grid line) and the CPU reference (reference::ReferenceScene, the
// same rays traced in double precision), which tests compare them with.

#include "strata/contour/Dexels.h"
#include "strata/mesh/Mesh.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"

namespace strata::remesh {

// The cells along the longest side of the box that --export takes by
// default, and the range it accepts.
constexpr int kDefaultResolution = 512;
constexpr int kLeastResolution = 8;
constexpr int kMostResolution = 4096;

// The sampling grid for `box` (the result's, or a box that holds it) at
// `resolution` cells along its longest side: the grid's outer vertices lie
// at least half a cell outside the box, and its planes are offset from the
// box's faces by an irrational fraction of a cell, so that the faces of
// typical models, at round coordinates, rarely lie on a grid plane. Throws
// strata::Error for an empty or flat box or a resolution out of range.
contour::DexelGrid gridFor(const mesh::Bounds& box, int resolution);

// The result's crossings along every grid line, by the GPU (the renderer
// holds the scene: setScene). `settings` as for a frame (layers, memory
// budget). Throws strata::Error where the driver could not walk every ray
// (llvmpipe's loop limit on very deep pixels). Reports progress per axis.
contour::Dexels sampleOnGpu(render::Renderer& renderer, const contour::DexelGrid& grid,
                            const render::RenderSettings& settings);

// The same by the CPU reference, on `threads` threads (0: every core).
contour::Dexels sampleWithReference(const reference::ReferenceScene& scene, const contour::DexelGrid& grid,
                                    int threads = 0);

}  // namespace strata::remesh
