#pragma once
// One piece of CPU work run on several threads at once, each copy taking its
// own share (typically from a shared atomic counter), as the CPU reference's
// rows, a sampled export's rays and the exact join's regions are.

#include <functional>

namespace strata {

// The machine's hardware threads, at least 1.
int hardwareThreads();

// Runs `work` on `threads` threads, this one among them (fewer where the
// system will not start more: the work is the same, later), and returns when
// every copy has returned. The first exception any copy throws is rethrown
// here once all have finished; a copy that throws should first tell the
// others to stop taking shares.
void runOnThreads(int threads, const std::function<void()>& work);

}  // namespace strata
