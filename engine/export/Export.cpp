#include "strata/export/Export.h"

#include <vector>

#include "ExportParts.h"
#include "strata/core/Error.h"
#include "strata/io/ExportFormats.h"
#include "strata/io/FlatWriter.h"
#include "strata/io/MeshWriter.h"
#include "strata/model/SurfaceColors.h"

namespace strata::exporting {

StagedExport stageExport(const scene::Tree& tree, const model::Model& model, const std::string& path,
                         const ExportSettings& settings) {
    if (settings.sampled) return stageSampledMesh(tree, model, path, settings);
    if (io::isFlatPath(path)) {
        StagedExport out;
        out.file = stageFlatExport(tree, path);
        return out;
    }
    return stageExactMesh(tree, model, path, settings.faceColor);
}

void requireSolidModel(const scene::Tree& tree) {
    if (tree.isFlat()) {
        throw Error(SourceLocation{tree.source, 0, 0},
                    "a 2D model has no solid to export (export it as " + io::extensionList(io::ExportKind::Drawing) + ")");
    }
}

io::StagedFile stageResultMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                               const mesh::Mesh& result, const glm::vec4& faceColor, double reach) {
    if (result.triangles.empty())
        throw Error(SourceLocation{tree.source, 0, 0}, "the CSG result is empty: nothing to export");
    std::vector<glm::vec4> colors;
    if (const io::ExportFormat* format = io::exportFormatOf(path); format != nullptr && format->colors)
        colors = model::surfaceColors(result, tree, model, faceColor, reach);
    return io::stageMesh(path, result, colors);
}

}  // namespace strata::exporting
