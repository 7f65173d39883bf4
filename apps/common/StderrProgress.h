#pragma once
// Progress of long CPU work (strata/core/Progress.h) as lines on stderr, the
// way the reference ray caster reports: nothing for work that ends within a
// second, then at most one line a second, e.g.
//   strata-render: exact difference: 3 of 12 (2.4 s)
// A step can run long by itself (one exact boolean, one sweep of a flat
// shape's outlines): when no line has come for two seconds, the last step
// reported (or, before any, the phase) is said again with the time, then
// after twice as long each time (at most 30 s), so a long run never goes
// quiet:
//   strata-render: text: uniting 10000 glyphs (6.0 s)
// Reminders are for a person watching: they come where stderr is a terminal
// (a script that reads stderr gets the lines steps report, as before). One
// object per phase of work: the reminders run from its construction to its
// destruction.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

#include "strata/core/Progress.h"

namespace strata::apps {

class StderrProgress : public Progress {
public:
    // `phase`: what the work is, said until a step is reported ("building
    // the model"); `reminders`: whether to say a long step again.
    StderrProgress(std::string program, std::string phase, bool reminders = stderrIsATerminal());
    static bool stderrIsATerminal();
    ~StderrProgress() override;
    StderrProgress(const StderrProgress&) = delete;
    StderrProgress& operator=(const StderrProgress&) = delete;
    void update(const char* what, std::size_t done, std::size_t total) override;

private:
    using Clock = std::chrono::steady_clock;
    void say(Clock::time_point now);  // with mutex_ held
    void remind();                    // the reminders' thread

    std::string program_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::string what_;
    std::size_t done_ = 0, total_ = 0;
    Clock::time_point start_ = Clock::now();
    Clock::time_point last_ = start_;  // of the last line, or the start
    Clock::duration reminder_;         // the quiet after which the step is said again
    std::thread reminders_;
};

}  // namespace strata::apps
