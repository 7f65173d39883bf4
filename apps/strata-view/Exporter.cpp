#include "Exporter.h"

#include <chrono>
#include <utility>

#include "strata/core/Error.h"
#include "strata/geometry/Exact.h"
#include "strata/geometry/SurfaceColors.h"
#include "strata/io/MeshWriter.h"

namespace strata::view {

std::size_t exportExact(const LoadedScene& scene, const std::string& path, const glm::vec4& faceColor) {
    const scene::Tree& tree = scene.tree;
    if (tree.isFlat()) throw Error(SourceLocation{path, 0, 0}, "cannot export a 2D model (it has no solid)");
    geometry::Mesh result;
    if (tree.root >= 0) result = geometry::exactResult(tree, tree.root, scene.model.leafMeshes);
    if (result.triangles.empty()) throw Error(SourceLocation{path, 0, 0}, "cannot export: the CSG result is empty");
    std::vector<glm::vec4> colors;
    if (io::meshFormatOf(path) == io::MeshFormat::ThreeMf) {
        colors = geometry::surfaceColors(result, tree, scene.model, faceColor);
    }
    io::stageMesh(path, result, colors).commit();
    return result.triangles.size();
}

Exporter::~Exporter() {
    if (progress_) progress_->cancel();
    if (running_.valid()) running_.wait();
}

bool Exporter::start(const LoadedScene& scene, const std::string& path, const glm::vec4& faceColor) {
    if (busy()) return false;
    progress_ = std::make_shared<LoadProgress>();
    running_ = std::async(std::launch::async, [scene, path, faceColor, progress = progress_] {
        ExportResult result;
        result.path = path;
        const WorkOutcome outcome =
            runReporting(*progress, path, "export cancelled", [&] { result.triangles = exportExact(scene, path, faceColor); });
        result.error = outcome.error;
        result.cancelled = outcome.cancelled;
        result.milliseconds = outcome.milliseconds;
        return result;
    });
    return true;
}

std::optional<ExportResult> Exporter::poll() {
    if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    return running_.get();
}

std::string Exporter::progressText() const { return busy() && progress_ ? progress_->text() : std::string(); }

void Exporter::cancel() {
    if (busy() && progress_) progress_->cancel();
}

}  // namespace strata::view
