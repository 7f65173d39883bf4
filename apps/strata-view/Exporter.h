#pragma once
// Exports the shown model on a worker thread, as strata-render's --export
// does: sampled and contoured (the image-space export, its samples taken by
// the CPU reference, so the window keeps its GL context to itself), or
// exact (CGAL, --export-exact). Either can take seconds, and the window must
// keep answering, show where the work is and let it be cancelled. One
// export at a time.

#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "Loader.h"
#include "SceneFile.h"

namespace strata::view {

struct ExportResult {
    std::string path;
    std::string error;       // the one-line message; empty on success
    bool cancelled = false;
    std::size_t triangles = 0;
    double milliseconds = 0;
    std::vector<std::string> warnings;  // written all the same
};

class Exporter {
public:
    ~Exporter();  // cancels a running export and waits for it to stop at its next step

    // Starts exporting `scene` (copied) into `path` (a mesh format of
    // io::exportFormats()): exact, or sampled at `resolution` cells along the result's
    // longest side; false, with nothing started, while another export runs.
    bool start(const LoadedScene& scene, const std::string& path, const glm::vec4& faceColor, bool exact,
               int resolution);
    // The finished export, if one finished since the last call.
    std::optional<ExportResult> poll();
    bool busy() const { return running_.valid(); }
    std::string progressText() const;
    void cancel();

private:
    std::future<ExportResult> running_;
    std::shared_ptr<LoadProgress> progress_;
};

}  // namespace strata::view
