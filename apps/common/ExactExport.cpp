#include "ExactExport.h"

#include <vector>

#include "strata/core/Error.h"
#include "strata/geometry/Exact.h"
#include "strata/geometry/SurfaceColors.h"
#include "strata/io/MeshWriter.h"

namespace strata::apps {

ExactExport stageExactExport(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                             const glm::vec4& faceColor) {
    const SourceLocation scene{tree.source, 0, 0};
    if (tree.isFlat()) throw Error(scene, "a 2D model has no solid to export (OpenSCAD exports it as DXF or SVG)");
    geometry::Mesh result;
    if (tree.root >= 0) result = geometry::exactResult(tree, tree.root, model.leafMeshes);
    if (result.triangles.empty()) throw Error(scene, "the CSG result is empty: nothing to export");
    std::vector<glm::vec4> colors;
    if (io::meshFormatOf(path) == io::MeshFormat::ThreeMf) colors = geometry::surfaceColors(result, tree, model, faceColor);
    return ExactExport{io::stageMesh(path, result, colors), result.triangles.size()};
}

}  // namespace strata::apps
