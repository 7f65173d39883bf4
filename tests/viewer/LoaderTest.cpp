// The viewer's background loads (apps/strata-view/Loader.h): a load that
// takes CPU work says where it is, and a cancel stops it at its next step,
// as a cancelled load (not an error), leaving the loader ready for the next.

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>
#include <thread>

#include "Loader.h"
#include "TempDir.h"

using strata::testing::TempDir;
using strata::view::LoadResult;
using strata::view::Loader;

namespace {

// Waits for the running load's result (at most a minute).
LoadResult finish(Loader& loader) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (std::chrono::steady_clock::now() < deadline) {
        if (std::optional<LoadResult> r = loader.poll()) return std::move(*r);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ADD_FAILURE() << "the load did not finish";
    return {};
}

// Eight exact differences of fine spheres: about a second of CGAL's time,
// far longer than the moment between a request and its cancel.
std::string slowScene() {
    std::string text = "hull() { union() {\n";
    for (int i = 0; i < 8; ++i) {
        const std::string x = std::to_string(3 * i);
        text += "difference() { multmatrix([[1, 0, 0, " + x + "], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                "sphere($fn = 64, r = 1); multmatrix([[1, 0, 0, " + x + ".5], [0, 1, 0, 0], [0, 0, 1, 0.5], "
                "[0, 0, 0, 1]]) sphere($fn = 64, r = 1); }\n";
    }
    return text + "} }\n";
}

TEST(Loader, CancelStopsALongLoadAndTheNextLoadRuns) {
    TempDir dir;
    const std::string slow = dir.write("slow.csg", slowScene());
    const std::string quick = dir.write("quick.csg", "cube(size = 1);\n");
    Loader loader(nullptr);
    loader.request(slow);
    loader.request(quick);  // waits behind the slow one; a cancel drops it
    loader.cancel();
    const LoadResult cancelled = finish(loader);
    EXPECT_TRUE(cancelled.cancelled);
    EXPECT_FALSE(cancelled.scene.has_value());
    EXPECT_EQ(cancelled.error, slow + ": loading cancelled");
    EXPECT_FALSE(loader.busy());

    loader.request(quick);
    const LoadResult loaded = finish(loader);
    EXPECT_FALSE(loaded.cancelled);
    ASSERT_TRUE(loaded.scene.has_value()) << loaded.error;
    EXPECT_EQ(loaded.scene->tree.leaves.size(), 1u);
}

TEST(Loader, AFinishedLoadIsNotCancelled) {
    TempDir dir;
    const std::string quick = dir.write("quick.csg", "cube(size = 1);\n");
    Loader loader(nullptr);
    loader.request(quick);
    const LoadResult loaded = finish(loader);
    loader.cancel();  // nothing running: nothing happens
    EXPECT_FALSE(loaded.cancelled);
    EXPECT_TRUE(loaded.scene.has_value());
    EXPECT_TRUE(loader.progressText().empty());
}

TEST(Loader, ALoadStartedBeforeTheWindowIsTakenOverWhole) {
    // strata-view's first load waits a moment, and a slow one is handed to
    // the window's loader, still running: its result arrives there.
    TempDir dir;
    const std::string slow = dir.write("slow.csg", slowScene());
    Loader first(nullptr);
    first.request(slow);
    EXPECT_FALSE(first.waitFor(std::chrono::milliseconds(1)).has_value());
    ASSERT_TRUE(first.busy());
    Loader window(nullptr);
    window.takeOver(first);
    EXPECT_FALSE(first.busy());
    EXPECT_TRUE(window.busy());
    EXPECT_GE(window.runningSeconds(), 0.001);
    // Its cancel reaches the running load: the progress came over with it.
    window.cancel();
    const LoadResult cancelled = finish(window);
    EXPECT_TRUE(cancelled.cancelled);
    EXPECT_EQ(cancelled.path, slow);
    EXPECT_FALSE(first.poll().has_value());

    // A quick load is there within the wait.
    const std::string quick = dir.write("quick.csg", "cube(size = 1);\n");
    first.request(quick);
    const std::optional<LoadResult> soon = first.waitFor(std::chrono::seconds(30));
    ASSERT_TRUE(soon.has_value());
    EXPECT_TRUE(soon->scene.has_value()) << soon->error;
}

}  // namespace
