#pragma once
// The exact export, as strata-render's --export-exact and strata-view's
// export both run it: the whole tree's result evaluated by CGAL, each
// triangle given its leaf's colour when the format carries colours (3MF),
// staged for writing. Reports its steps to the calling thread's Progress.

#include <cstddef>
#include <string>

#include <glm/vec4.hpp>

#include "strata/geometry/Model.h"
#include "strata/io/ImageWriter.h"
#include "strata/scene/Tree.h"

namespace strata::apps {

// Rounds `mesh` to single precision (what STL and 3MF keep; every format
// gets the same points) and removes what rounding flattened (vertices
// brought together, triangles left without area), keeping it closed.
void roundForFile(geometry::Mesh& mesh);

struct ExactExport {
    io::StagedFile file;        // commit() puts it in place
    std::size_t triangles = 0;
};

// A 2D model's path names a drawing (.svg, .dxf): its 2D result is staged
// as one (stageFlatExport). Throws strata::Error naming the scene
// (tree.source) for a 2D model given a mesh path, a 3D model given a
// drawing path, or an empty result, and naming `path` when it cannot be
// written. `faceColor` is
// the colour of triangles whose leaf has no color().
ExactExport stageExactExport(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                             const glm::vec4& faceColor);

// The 2D result of a flat model (geometry::flatResult) staged as the drawing
// `path` names (SVG or DXF). Throws, naming the scene, for a 3D model or an
// empty result.
io::StagedFile stageFlatExport(const scene::Tree& tree, const std::string& path);

// What every export shares (this one and ImageExport.h). Throws, naming the
// scene, for a 2D model, which has no solid to export.
void requireSolidModel(const scene::Tree& tree);
// Throws, naming the scene, for an empty `result`; otherwise stages it for
// `path`, each triangle coloured by its leaf when the format carries colours
// (geometry::surfaceColors, with `reach` for a result that only
// approximates the leaves' faces).
io::StagedFile stageResultMesh(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                               const geometry::Mesh& result, const glm::vec4& faceColor, double reach = 0.0);

}  // namespace strata::apps
