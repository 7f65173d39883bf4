// runOnThreads (strata/core/Threads.h): every share taken once whatever the
// thread count, and a copy's exception rethrown after all have returned.

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "strata/core/Threads.h"

TEST(RunOnThreads, EveryShareIsTakenOnceOnAnyNumberOfThreads) {
    for (int threads : {1, 2, 7}) {
        std::vector<std::atomic<int>> taken(1000);
        std::atomic<std::size_t> next{0};
        strata::runOnThreads(threads, [&] {
            for (std::size_t i = next++; i < taken.size(); i = next++) ++taken[i];
        });
        for (const std::atomic<int>& t : taken) EXPECT_EQ(t.load(), 1) << threads << " threads";
    }
}

TEST(RunOnThreads, AThrowingCopyIsRethrownAfterTheOthersReturn) {
    std::atomic<int> returned{0};
    std::atomic<int> started{0};
    EXPECT_THROW(strata::runOnThreads(4,
                                      [&] {
                                          if (started++ == 0) throw std::runtime_error("share failed");
                                          ++returned;
                                      }),
                 std::runtime_error);
    // The call came back only after every copy had: all but the thrower returned.
    EXPECT_EQ(returned.load(), started.load() - 1);
    EXPECT_GE(strata::hardwareThreads(), 1);
}
