#include "Exporter.h"

#include <chrono>
#include <exception>
#include <utility>

#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/geometry/Exact.h"
#include "strata/io/MeshWriter.h"

namespace strata::view {

std::size_t exportExact(const LoadedScene& scene, const std::string& path) {
    const scene::Tree& tree = scene.tree;
    if (tree.isFlat()) throw Error(SourceLocation{path, 0, 0}, "cannot export a 2D model (it has no solid)");
    geometry::Mesh result;
    if (tree.root >= 0) result = geometry::exactResult(tree, tree.root, scene.model.leafMeshes);
    if (result.triangles.empty()) throw Error(SourceLocation{path, 0, 0}, "cannot export: the CSG result is empty");
    io::stageMesh(path, result).commit();
    return result.triangles.size();
}

Exporter::~Exporter() {
    if (progress_) progress_->cancel();
    if (running_.valid()) running_.wait();
}

bool Exporter::start(const LoadedScene& scene, const std::string& path) {
    if (busy()) return false;
    progress_ = std::make_shared<LoadProgress>();
    running_ = std::async(std::launch::async, [scene, path, progress = progress_] {
        ExportResult result;
        result.path = path;
        const auto start = std::chrono::steady_clock::now();
        try {
            const ProgressScope scope(progress.get());
            result.triangles = exportExact(scene, path);
        } catch (const Cancelled&) {
            result.cancelled = true;
            result.error = path + ": export cancelled";
        } catch (const Error& e) {
            result.error = e.what();
        } catch (const std::exception& e) {
            result.error = path + ": " + e.what();
        }
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
