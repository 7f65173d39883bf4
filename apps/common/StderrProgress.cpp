#include "StderrProgress.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include <unistd.h>

namespace strata::apps {

namespace {
constexpr auto kQuiet = std::chrono::seconds(1);  // no line before, nor two lines within
// While a step runs on, reminders come after 2 s without a line, then
// twice as long each time, at most every 30 s.
constexpr auto kFirstReminder = std::chrono::seconds(2);
constexpr auto kLongestReminder = std::chrono::seconds(30);
}  // namespace

StderrProgress::StderrProgress(std::string program, std::string phase, bool reminders)
    : program_(std::move(program)), what_(std::move(phase)), reminder_(kFirstReminder) {
    if (reminders) reminders_ = std::thread([this] { remind(); });
}

StderrProgress::~StderrProgress() {
    if (!reminders_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    reminders_.join();
}

bool StderrProgress::stderrIsATerminal() { return isatty(STDERR_FILENO) == 1; }

void StderrProgress::say(Clock::time_point now) {
    last_ = now;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    if (total_ > 0) {
        std::fprintf(stderr, "%s: %s: %zu of %zu (%.1f s)\n", program_.c_str(), what_.c_str(), done_, total_, seconds);
    } else {
        std::fprintf(stderr, "%s: %s (%.1f s)\n", program_.c_str(), what_.c_str(), seconds);
    }
}

void StderrProgress::update(const char* what, std::size_t done, std::size_t total) {
    const Clock::time_point now = Clock::now();
    std::lock_guard lock(mutex_);
    if (what_ != what) reminder_ = kFirstReminder;  // a new step
    what_ = what;
    done_ = done;
    total_ = total;
    if (now - last_ >= kQuiet) say(now);
}

void StderrProgress::remind() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
        wake_.wait_for(lock, kQuiet / 2);
        if (stop_) break;
        const Clock::time_point now = Clock::now();
        if (now - start_ >= kFirstReminder && now - last_ >= reminder_) {
            say(now);
            reminder_ = std::min<Clock::duration>(2 * reminder_, kLongestReminder);
        }
    }
}

}  // namespace strata::apps
