// Progress lines on stderr (apps/common/StderrProgress.h): quiet for work
// that ends within a second, and while one step runs on, reminders of it.

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "StderrProgress.h"

using strata::apps::StderrProgress;

namespace {

int lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n' ? 1 : 0;
    return n;
}

}  // namespace

TEST(StderrProgress, ShortWorkSaysNothing) {
    testing::internal::CaptureStderr();
    {
        StderrProgress progress("prog", "building the model", true);
        progress.update("meshing leaves", 0, 3);
        progress.update("meshing leaves", 1, 3);
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(StderrProgress, OneLongStepIsSaidAgainAfterTwoSeconds) {
    testing::internal::CaptureStderr();
    {
        StderrProgress progress("prog", "building the model", true);
        progress.update("text: uniting 9 glyphs", 0, 0);
        // The first reminder comes at 2 s, the next 4 s after it.
        std::this_thread::sleep_for(std::chrono::milliseconds(3200));
    }
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_EQ(lines(said), 1) << said;
    EXPECT_EQ(said.rfind("prog: text: uniting 9 glyphs (2.", 0), 0u) << said;
}

TEST(StderrProgress, NoRemindersUnlessAskedFor) {
    testing::internal::CaptureStderr();
    {
        StderrProgress progress("prog", "exporting", false);
        std::this_thread::sleep_for(std::chrono::milliseconds(2300));
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(StderrProgress, BeforeAnyStepThePhaseIsSaid) {
    testing::internal::CaptureStderr();
    {
        StderrProgress progress("prog", "exporting", true);
        std::this_thread::sleep_for(std::chrono::milliseconds(2600));
    }
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_EQ(said.rfind("prog: exporting (2.", 0), 0u) << said;
}
