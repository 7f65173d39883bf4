// RecentFiles: the files strata-view opened last, kept in a text file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "RecentFiles.h"

using strata::view::RecentFiles;

namespace {

namespace fs = std::filesystem;

class RecentFilesTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("strata-recent-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string store() const { return (dir_ / "state" / "recent-files").string(); }
    fs::path dir_;
};

}  // namespace

TEST_F(RecentFilesTest, NewestFirstOnceEachAtMostTen) {
    RecentFiles recent(store());
    EXPECT_TRUE(recent.files().empty());
    for (int k = 0; k < 12; ++k) EXPECT_EQ(recent.add("/models/m" + std::to_string(k) + ".scad"), "");
    EXPECT_EQ(recent.add("/models/m5.scad"), "");
    ASSERT_EQ(recent.files().size(), RecentFiles::kMax);
    EXPECT_EQ(recent.files()[0], "/models/m5.scad");
    EXPECT_EQ(recent.files()[1], "/models/m11.scad");
    EXPECT_EQ(recent.files()[9], "/models/m2.scad");  // m0 and m1 fell off the end
    // The next session reads the same list.
    EXPECT_EQ(RecentFiles(store()).files(), recent.files());
}

TEST_F(RecentFilesTest, PathsAreKeptAbsolute) {
    RecentFiles recent(store());
    recent.add("relative/../a.csg");
    ASSERT_EQ(recent.files().size(), 1u);
    EXPECT_EQ(recent.files()[0], (fs::current_path() / "a.csg").string());
}

TEST_F(RecentFilesTest, LinesThatNameNoFileAreSkipped) {
    fs::create_directories(dir_ / "state");
    std::ofstream(store()) << "/a.scad\n\nrelative.scad\n/b\x1b]0;title\a.scad\n/a.scad\n/c.csg\n";
    EXPECT_EQ(RecentFiles(store()).files(), (std::vector<std::string>{"/a.scad", "/c.csg"}));
}

TEST_F(RecentFilesTest, AStoreThatCannotBeWrittenKeepsTheListForTheSession) {
    std::ofstream(dir_ / "state") << "a file where the folder should be";
    RecentFiles recent(store());
    EXPECT_EQ(recent.add("/a.scad"), "cannot keep the recent files in " + store());
    EXPECT_EQ(recent.files(), std::vector<std::string>{"/a.scad"});
    RecentFiles none("");
    EXPECT_EQ(none.add("/b.scad"), "");
    EXPECT_EQ(none.files(), std::vector<std::string>{"/b.scad"});
}
