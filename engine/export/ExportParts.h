#pragma once
// The export room's parts, for its own files: the exact and the sampled
// mesh, the 2D drawing, and what they share. Hosts call stageExport
// (strata/export/Export.h).

#include <string>

#include <glm/vec4.hpp>

#include "strata/export/Export.h"
#include "strata/mesh/Mesh.h"

namespace strata::exporting {

// The exact result as every mesh file holds it (ExactExport.cpp).
StagedExport stageExactMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                            const glm::vec4& faceColor);

// The sampled result's mesh (SampledExport.cpp).
StagedExport stageSampledMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                              const ExportSettings& settings);

// The 2D result of a flat model (model::flatResult) staged as the drawing
// `path` names (SVG or DXF). Throws, naming the scene, for a 3D model or an
// empty result (ExactExport.cpp).
io::StagedFile stageFlatExport(const scene::Tree& tree, const std::string& path);

// Rounds `mesh` to single precision (what STL and 3MF keep; every format
// gets the same points) and removes what rounding flattened (vertices
// brought together, triangles left without area), keeping it closed, in
// mesh::canonicalOrder (ExactExport.cpp).
void roundForFile(mesh::Mesh& mesh);

// What both meshes share (Export.cpp). Throws, naming the scene, for a 2D
// model, which has no solid to export.
void requireSolidModel(const scene::Tree& tree);
// Throws, naming the scene, for an empty `result`; otherwise stages it for
// `path`, each triangle coloured by its leaf when the format carries colours
// (model::surfaceColors, with `reach` for a result that only
// approximates the leaves' faces).
io::StagedFile stageResultMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                               const mesh::Mesh& result, const glm::vec4& faceColor, double reach = 0.0);

}  // namespace strata::exporting
