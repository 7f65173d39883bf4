#pragma once
// The image-space export, as strata-render's --export and strata-view's
// export run it: the result sampled along three axes (by the GPU's result
// peel, or by the CPU reference), contoured into a closed mesh, each
// triangle given its leaf's colour when the format carries colours (3MF),
// staged for writing. Reports its steps to the calling thread's Progress.

#include <cstddef>
#include <string>

#include <glm/vec4.hpp>

#include "strata/geometry/Model.h"
#include "strata/io/ImageWriter.h"
#include "strata/remesh/Remesh.h"
#include "strata/scene/Tree.h"

namespace strata::apps {

struct ImageExportSettings {
    int resolution = remesh::kDefaultResolution;  // cells along the longest side of the result's box
    bool reference = false;                       // sample with the CPU reference instead of the GPU
};

struct ImageExport {
    io::StagedFile file;  // commit() puts it in place
    std::size_t triangles = 0;
    double sampleMs = 0, contourMs = 0;
};

// Throws strata::Error naming the scene (tree.source) for a 2D model or an
// empty result, and naming `path` when it cannot be written. The GPU path
// makes its own headless GL context; call it where no other is current.
ImageExport stageImageExport(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                             const glm::vec4& faceColor, const ImageExportSettings& settings);

}  // namespace strata::apps
