#include "Exporter.h"

#include <chrono>
#include <utility>

#include "Worker.h"
#include "strata/export/Export.h"

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
            exporting::ExportSettings settings;
            settings.sampled = !exact;
            settings.resolution = resolution;
            settings.reference = true;  // the viewer's GL context is the window's, on another thread
            settings.faceColor = faceColor;
            exporting::StagedExport exported = exporting::stageExport(scene.tree, scene.model, path, settings);
            exported.file.commit();
            result.triangles = exported.triangles;
            for (const Warning& w : exported.warnings) result.warnings.push_back(w.message);
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
