#pragma once
// Progress of long CPU work (strata/core/Progress.h) as lines on stderr, the
// way the reference ray caster reports: nothing for work that ends within a
// second, then at most one line a second, e.g.
//   strata-render: exact difference: 3 of 12 (2.4 s)

#include <chrono>
#include <string>

#include "strata/core/Progress.h"

namespace strata::apps {

class StderrProgress : public Progress {
public:
    explicit StderrProgress(std::string program);
    void update(const char* what, std::size_t done, std::size_t total) override;

private:
    using Clock = std::chrono::steady_clock;
    std::string program_;
    Clock::time_point start_ = Clock::now();
    Clock::time_point last_ = start_;
};

}  // namespace strata::apps
