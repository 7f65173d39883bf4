#include "Exporter.h"

#include <chrono>
#include <utility>

#include "ExactExport.h"
#include "ImageExport.h"
#include "Worker.h"

namespace strata::view {

Exporter::~Exporter() {
    if (progress_) progress_->cancel();
    if (running_.valid()) running_.wait();
}

bool Exporter::start(const LoadedScene& scene, const std::string& path, const glm::vec4& faceColor, bool exact,
                     int resolution) {
    if (busy()) return false;
    progress_ = std::make_shared<LoadProgress>();
    running_ = apps::startWorker([scene, path, faceColor, exact, resolution, progress = progress_] {
        ExportResult result;
        result.path = path;
        const WorkOutcome outcome = runReporting(*progress, path, "export cancelled", [&] {
            if (exact) {
                apps::ExactExport exported = apps::stageExactExport(scene.tree, scene.model, path, faceColor);
                exported.file.commit();
                result.triangles = exported.triangles;
                return;
            }
            apps::ImageExportSettings settings;
            settings.resolution = resolution;
            settings.reference = true;
            apps::ImageExport exported = apps::stageImageExport(scene.tree, scene.model, path, faceColor, settings);
            exported.file.commit();
            result.triangles = exported.triangles;
        });
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
