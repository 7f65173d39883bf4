#pragma once
// Loads scene files on a worker thread: parsing and tessellation are CPU work
// that can take seconds for a large file, and the window must keep answering
// meanwhile. The GL upload (Renderer::setScene) stays on the GL thread: the
// caller polls for the result there.

#include <chrono>
#include <functional>
#include <future>
#include <optional>
#include <string>

#include "SceneFile.h"

namespace strata::view {

struct LoadResult {
    std::string path;
    std::optional<LoadedScene> scene;  // empty on failure
    std::string error;                 // the one-line message on failure
    double milliseconds = 0;
};

class Loader {
public:
    // `wake` is called on the worker thread when a load has finished (to wake
    // an event loop that waits for input); it must be thread-safe.
    explicit Loader(std::function<void()> wake);
    ~Loader();  // waits for a running load: it cannot be interrupted halfway
    Loader(const Loader&) = delete;
    Loader& operator=(const Loader&) = delete;

    // Starts loading `path`; while a load runs, the newest request waits for it.
    void request(const std::string& path);
    // The finished load, if one finished since the last call. Starts a waiting request.
    std::optional<LoadResult> poll();
    bool busy() const;
    // How long the running load has taken so far.
    double runningSeconds() const;

private:
    void start(const std::string& path);

    std::function<void()> wake_;
    std::future<LoadResult> running_;
    std::optional<std::string> waiting_;
    std::chrono::steady_clock::time_point started_;
};

}  // namespace strata::view
