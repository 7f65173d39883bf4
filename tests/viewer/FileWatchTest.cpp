// Reload detection (apps/strata-view/FileWatch.h): an editor's atomic save
// (new file renamed over the old one) and an in-place rewrite both count once.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "FileWatch.h"
#include "TempDir.h"

using strata::testing::TempDir;

TEST(FileWatch, SeesRenamesAndRewritesOnceAndWaitsOutAMissingFile) {
    TempDir dir;
    const std::string path = dir.write("a.csg", "cube();\n");
    strata::view::FileWatch watch(path);
    EXPECT_FALSE(watch.changed());

    // An editor's save: same size, new inode.
    const std::string temp = dir.write("a.csg.tmp", "cube();\n");
    std::filesystem::rename(temp, path);
    EXPECT_TRUE(watch.changed());
    EXPECT_FALSE(watch.changed());

    // In place, a different size.
    std::ofstream(path, std::ios::app) << "sphere();\n";
    EXPECT_TRUE(watch.changed());

    // Gone (between an unlink and a rename): no change until it is back.
    std::filesystem::remove(path);
    EXPECT_FALSE(watch.changed());
    dir.write("a.csg", "cube(2);\n");
    EXPECT_TRUE(watch.changed());
}
