#pragma once
// Work on a thread of its own whose stack has a known size. Loading a scene
// builds its model, which recurses once for every hull, minkowski, resize,
// projection or extrusion inside another (the parser's budget caps how many,
// docs/limits.md); a thread from std::async gets whatever stack the
// environment gives new threads (`ulimit -s`), which may be less, and the
// main thread whatever `ulimit -s` gives it (sanitizer builds use several
// times the stack a level). strata-view loads and exports on such threads;
// strata-render does all its work on one.

#include <pthread.h>

#include <cstddef>
#include <exception>
#include <future>
#include <memory>
#include <system_error>
#include <utility>

namespace strata::apps {

inline constexpr std::size_t kWorkerStackBytes = std::size_t(64) << 20;

// Runs `work` on a new thread with a stack of kWorkerStackBytes; the future
// is ready once the thread has let go of everything `work` held.
template <class F>
auto startWorker(F work) -> std::future<decltype(work())> {
    using Result = decltype(work());
    struct Job {
        F work;
        std::promise<Result> promise;
    };
    auto job = std::make_unique<Job>(Job{std::move(work), {}});
    std::future<Result> result = job->promise.get_future();
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstacksize(&attr, kWorkerStackBytes);
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    pthread_t thread;
    auto run = [](void* p) -> void* {
        std::unique_ptr<Job> owned(static_cast<Job*>(p));
        std::promise<Result> promise = std::move(owned->promise);
        try {
            Result value = owned->work();
            owned.reset();
            promise.set_value_at_thread_exit(std::move(value));
        } catch (...) {
            owned.reset();
            promise.set_exception_at_thread_exit(std::current_exception());
        }
        return nullptr;
    };
    const int failed = pthread_create(&thread, &attr, run, job.get());
    pthread_attr_destroy(&attr);
    if (failed != 0) throw std::system_error(failed, std::generic_category(), "cannot start a worker thread");
    job.release();  // the thread owns it now
    return result;
}

}  // namespace strata::apps
