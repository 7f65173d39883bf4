#pragma once
// Loads scene files on a worker thread: parsing and tessellation are CPU work
// that can take seconds for a large file, and the window must keep answering
// meanwhile. The GL upload (Renderer::setScene) stays on the GL thread: the
// caller polls for the result there.

#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "SceneFile.h"
#include "strata/core/Progress.h"

namespace strata::view {

struct LoadResult {
    std::string path;
    std::optional<LoadedScene> scene;  // empty on failure
    std::string error;                 // the one-line message on failure
    bool cancelled = false;            // stopped by Loader::cancel (no error in the file)
    double milliseconds = 0;           // parsing and meshing, on the worker
    // When Loader::request asked for it (for a reload: when the file watch
    // saw the change), so that any wait behind a running load is after it.
    std::chrono::steady_clock::time_point requested;
    std::chrono::steady_clock::time_point finished;  // when the worker was done with it
};

// What a running load reports (strata/core/Progress.h), read by the GL
// thread while the worker writes it.
class LoadProgress : public Progress {
public:
    void update(const char* what, std::size_t done, std::size_t total) override;
    bool cancelled() const override { return cancel_.load(); }
    void cancel() { cancel_ = true; }
    // "exact difference: 3 of 12", or empty before the first report.
    std::string text() const;

private:
    mutable std::mutex mutex_;
    std::string what_;
    std::size_t done_ = 0, total_ = 0;
    std::atomic<bool> cancel_{false};
};

// How background work ended: its one-line error ("" on success), whether it
// stopped because it was asked to, and how long it took.
struct WorkOutcome {
    std::string error;
    bool cancelled = false;
    double milliseconds = 0;
};

// Runs `work` on the calling thread with `progress` as its sink, turning
// every way it can end into a WorkOutcome; `path` names the file in messages
// that do not already, `cancelledMessage` follows it when it was cancelled.
WorkOutcome runReporting(LoadProgress& progress, const std::string& path, const char* cancelledMessage,
                         const std::function<void()>& work);

class Loader {
public:
    // `wake` is called on the worker thread when a load has finished (to wake
    // an event loop that waits for input); it must be thread-safe.
    explicit Loader(std::function<void()> wake);
    ~Loader();  // cancels a running load and waits for it to stop at its next step
    Loader(const Loader&) = delete;
    Loader& operator=(const Loader&) = delete;

    // Starts loading `path`; while a load runs, the newest request waits for it.
    void request(const std::string& path);
    // The finished load, if one finished since the last call. Starts a waiting request.
    std::optional<LoadResult> poll();
    bool busy() const;
    // How long the running load has taken so far.
    double runningSeconds() const;
    // Where the running load is ("exact difference: 3 of 12"), or empty.
    std::string progressText() const;
    // Asks the running load to stop at its next step (the last good model
    // stays); a waiting request is dropped.
    void cancel();
    // poll(), after waiting up to `limit` for the running load to finish.
    std::optional<LoadResult> waitFor(std::chrono::milliseconds limit);
    // Takes over `other`'s running load and waiting request, if any (its
    // progress and start time with it); `other` is then idle. This one's
    // own load, if any, is cancelled and waited for first.
    void takeOver(Loader& other);

private:
    void start(const std::string& path, std::chrono::steady_clock::time_point requested);

    std::function<void()> wake_;
    std::future<LoadResult> running_;
    std::shared_ptr<LoadProgress> progress_;
    std::optional<std::string> waiting_;
    std::chrono::steady_clock::time_point waitingRequested_;
    std::chrono::steady_clock::time_point started_;
};

}  // namespace strata::view
