#include "ImageExport.h"

#include <chrono>
#include <vector>

#include "strata/camera/ViewBounds.h"
#include "strata/contour/Contour.h"
#include "strata/core/Error.h"
#include "strata/geometry/SurfaceColors.h"
#include "strata/gpu/Context.h"
#include "strata/io/MeshWriter.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"

namespace strata::apps {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

contour::Dexels sample(const scene::Tree& tree, const geometry::Model& model, const contour::DexelGrid& grid,
                       const ImageExportSettings& settings) {
    if (settings.reference) return remesh::sampleWithReference(reference::ReferenceScene(tree, model), grid);
    gpu::Context context;  // made first, destroyed last
    render::Renderer renderer;
    renderer.setScene(tree, model);
    render::RenderSettings frame;
    frame.layers = settings.layers;
    return remesh::sampleOnGpu(renderer, grid, frame);
}

}  // namespace

ImageExport stageImageExport(const scene::Tree& tree, const geometry::Model& model, const std::string& path,
                             const glm::vec4& faceColor, const ImageExportSettings& settings) {
    const SourceLocation scene{tree.source, 0, 0};
    if (tree.isFlat()) throw Error(scene, "a 2D model has no solid to export (OpenSCAD exports it as DXF or SVG)");
    const geometry::Bounds box = render::viewBounds(tree, model);
    if (tree.root < 0 || box.empty()) throw Error(scene, "the CSG result is empty: nothing to export");
    ImageExport out;
    auto t = Clock::now();
    const contour::DexelGrid grid = remesh::gridFor(box, settings.resolution);
    const contour::Dexels dexels = sample(tree, model, grid, settings);
    out.sampleMs = msSince(t);
    t = Clock::now();
    const geometry::Mesh result = contour::contour(dexels);
    out.contourMs = msSince(t);
    if (result.triangles.empty()) throw Error(scene, "the CSG result is empty: nothing to export");
    std::vector<glm::vec4> colors;
    if (io::meshFormatOf(path) == io::MeshFormat::ThreeMf)
        colors = geometry::surfaceColors(result, tree, model, faceColor, grid.spacing);
    out.triangles = result.triangles.size();
    out.file = io::stageMesh(path, result, colors);
    return out;
}

}  // namespace strata::apps
