#include "Loader.h"

#include <exception>
#include <utility>

#include "Worker.h"
#include "strata/core/Error.h"
#include "strata/core/Timing.h"

namespace strata::view {

Loader::Loader(std::function<void()> wake) : wake_(std::move(wake)) {}

void LoadProgress::update(const char* what, std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(mutex_);
    what_ = what;
    done_ = done;
    total_ = total;
}

std::string LoadProgress::text() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (what_.empty() || total_ == 0) return what_;
    return what_ + ": " + std::to_string(done_) + " of " + std::to_string(total_);
}

WorkOutcome runReporting(LoadProgress& progress, const std::string& path, const char* cancelledMessage,
                         const std::function<void()>& work) {
    WorkOutcome outcome;
    const auto start = std::chrono::steady_clock::now();
    try {
        const ProgressScope scope(&progress);
        work();
    } catch (const Cancelled&) {
        outcome.cancelled = true;
        outcome.error = path + ": " + cancelledMessage;
    } catch (const Error& e) {
        outcome.error = e.what();
    } catch (const std::exception& e) {
        // Not ours (std::bad_alloc, a library's exception): still one line.
        outcome.error = path + ": " + e.what();
    }
    outcome.milliseconds = msSince(start);
    return outcome;
}

Loader::~Loader() {
    if (progress_) progress_->cancel();
    if (running_.valid()) running_.wait();
}

void Loader::start(const std::string& path, std::chrono::steady_clock::time_point requested) {
    started_ = std::chrono::steady_clock::now();
    progress_ = std::make_shared<LoadProgress>();
    running_ = apps::startWorker([path, requested, wake = wake_, progress = progress_] {
        LoadResult result;
        result.path = path;
        result.requested = requested;
        const WorkOutcome outcome =
            runReporting(*progress, path, "loading cancelled", [&] { result.scene = loadSceneFile(path); });
        result.error = outcome.error;
        result.cancelled = outcome.cancelled;
        result.milliseconds = outcome.milliseconds;
        result.finished = std::chrono::steady_clock::now();
        if (wake) wake();
        return result;
    });
}

void Loader::request(const std::string& path) {
    const auto now = std::chrono::steady_clock::now();
    if (busy()) {
        waiting_ = path;
        waitingRequested_ = now;
    } else {
        start(path, now);
    }
}

std::optional<LoadResult> Loader::poll() {
    if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return std::nullopt;
    LoadResult result = running_.get();
    if (waiting_) {
        start(*waiting_, waitingRequested_);
        waiting_.reset();
    }
    return result;
}

bool Loader::busy() const { return running_.valid(); }

std::string Loader::progressText() const { return busy() && progress_ ? progress_->text() : std::string(); }

void Loader::cancel() {
    waiting_.reset();
    if (busy() && progress_) progress_->cancel();
}

double Loader::runningSeconds() const {
    return busy() ? std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count() : 0.0;
}

std::optional<LoadResult> Loader::waitFor(std::chrono::milliseconds limit) {
    if (running_.valid()) running_.wait_for(limit);
    return poll();
}

void Loader::takeOver(Loader& other) {
    if (&other == this) return;
    if (progress_) progress_->cancel();
    if (running_.valid()) running_.wait();
    running_ = std::move(other.running_);
    progress_ = std::move(other.progress_);
    waiting_ = std::move(other.waiting_);
    other.waiting_.reset();
    waitingRequested_ = other.waitingRequested_;
    started_ = other.started_;
}

}  // namespace strata::view
