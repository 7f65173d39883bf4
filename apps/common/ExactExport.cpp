#include "ExactExport.h"

#include <vector>

#include "strata/core/Error.h"
#include "strata/geometry/Exact.h"
#include "strata/geometry/SurfaceColors.h"
#include "strata/io/MeshWriter.h"

namespace strata::apps {

void requireSolidModel(const scene::Tree& tree) {
    if (tree.isFlat()) {
        throw Error(SourceLocation{tree.source, 0, 0},
                    "a 2D model has no solid to export (OpenSCAD exports it as DXF or SVG)");
    }
}

io::StagedFile stageResultMesh(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                               const geometry::Mesh& result, const glm::vec4& faceColor, double reach) {
    if (result.triangles.empty())
        throw Error(SourceLocation{tree.source, 0, 0}, "the CSG result is empty: nothing to export");
    std::vector<glm::vec4> colors;
    if (io::meshFormatOf(path) == io::MeshFormat::ThreeMf)
        colors = geometry::surfaceColors(result, tree, model, faceColor, reach);
    return io::stageMesh(path, result, colors);
}

ExactExport stageExactExport(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                             const glm::vec4& faceColor) {
    requireSolidModel(tree);
    geometry::Mesh result;
    if (tree.root >= 0) result = geometry::exactResult(tree, tree.root, model.leafMeshes);
    return ExactExport{stageResultMesh(tree, model, path, result, faceColor), result.triangles.size()};
}

}  // namespace strata::apps
