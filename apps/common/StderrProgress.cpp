#include "StderrProgress.h"

#include <cstdio>
#include <utility>

namespace strata::apps {

StderrProgress::StderrProgress(std::string program) : program_(std::move(program)) {}

void StderrProgress::update(const char* what, std::size_t done, std::size_t total) {
    const Clock::time_point now = Clock::now();
    if (now - last_ < std::chrono::seconds(1)) return;
    last_ = now;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    if (total > 0) {
        std::fprintf(stderr, "%s: %s: %zu of %zu (%.1f s)\n", program_.c_str(), what, done, total, seconds);
    } else {
        std::fprintf(stderr, "%s: %s (%.1f s)\n", program_.c_str(), what, seconds);
    }
}

}  // namespace strata::apps
