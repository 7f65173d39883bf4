#include "Loader.h"

#include <exception>
#include <utility>

#include "strata/core/Error.h"

namespace strata::view {

Loader::Loader(std::function<void()> wake) : wake_(std::move(wake)) {}

Loader::~Loader() {
    if (running_.valid()) running_.wait();
}

void Loader::start(const std::string& path) {
    started_ = std::chrono::steady_clock::now();
    running_ = std::async(std::launch::async, [path, wake = wake_] {
        LoadResult result;
        result.path = path;
        const auto start = std::chrono::steady_clock::now();
        try {
            result.scene = loadSceneFile(path);
        } catch (const Error& e) {
            result.error = e.what();
        } catch (const std::exception& e) {
            // Not ours (std::bad_alloc, a library's exception): still one line.
            result.error = path + ": " + e.what();
        }
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (wake) wake();
        return result;
    });
}

void Loader::request(const std::string& path) {
    if (busy())
        waiting_ = path;
    else
        start(path);
}

std::optional<LoadResult> Loader::poll() {
    if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return std::nullopt;
    LoadResult result = running_.get();
    if (waiting_) {
        start(*waiting_);
        waiting_.reset();
    }
    return result;
}

bool Loader::busy() const { return running_.valid(); }

double Loader::runningSeconds() const {
    return busy() ? std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count() : 0.0;
}

}  // namespace strata::view
