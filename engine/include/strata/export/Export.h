#pragma once
// The CSG result written as a file: the one entry through which strata-render's
// --export, strata-view's export and an embedding host export a scene.
//
// A solid's result becomes a mesh (STL, OFF, OBJ, 3MF), a 2D model's a
// drawing (SVG, DXF); the path's extension picks the format from the one
// table in strata/io/ExportFormats.h. The mesh is either
//  - exact (the default): the tree evaluated by CGAL as OpenSCAD's render
//    does (strata/geometry/Exact.h), its points rounded to single precision;
//  - or sampled: the image-space result sampled along three axes, by the
//    GPU's result peel or the CPU reference (strata/remesh/Remesh.h), and
//    contoured into a closed mesh (strata/contour/Contour.h).
// Formats that keep colours (3MF) get each triangle's leaf colour. Reports
// its steps to the calling thread's Progress (strata/core/Progress.h).

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"
#include "strata/model/Model.h"
#include "strata/remesh/Remesh.h"
#include "strata/scene/Tree.h"

namespace strata::exporting {

struct ExportSettings {
    bool sampled = false;                         // the sampled mesh instead of the exact one
    int resolution = remesh::kDefaultResolution;  // sampled: cells along the longest side of the result's box
    bool reference = false;                       // sampled: by the CPU reference instead of the GPU
    glm::vec4 faceColor{1.0f};                    // the colour of triangles whose leaf has no color()
};

struct StagedExport {
    io::StagedFile file;  // commit() puts it in place
    std::size_t triangles = 0;
    double sampleMs = 0, contourMs = 0;  // the sampled mesh's two steps
    std::vector<Warning> warnings;       // written all the same (a sampled mesh that still crosses itself)
};

// Stages the export of `tree` (whose leaves `model` holds) as `path`; nothing
// is written until the file is committed. Throws strata::Error naming the
// scene (tree.source) for a 2D model given a mesh path, a 3D model given a
// drawing path, an empty result, or a sampling grid too coarse for a wall of
// the solid, and naming `path` when it cannot be written. The GPU sampler
// makes its own headless GL context: call it where no other is current.
StagedExport stageExport(const scene::Tree& tree, const model::Model& model, const std::string& path,
                         const ExportSettings& settings);

}  // namespace strata::exporting
