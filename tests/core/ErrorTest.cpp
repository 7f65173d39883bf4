#include <gtest/gtest.h>

#include "strata/core/Error.h"

using strata::Error;
using strata::SourceLocation;

TEST(Error, MessageStartsWithFileLineAndColumn) {
    Error e(SourceLocation{"scenes/gear.csg", 12, 5}, "unknown primitive 'cyl'");
    EXPECT_STREQ(e.what(), "scenes/gear.csg:12:5: unknown primitive 'cyl'");
}

TEST(Error, LocationLeavesOutWhatIsUnknown) {
    EXPECT_EQ((SourceLocation{"a.stl", 0, 0}.str()), "a.stl");
    EXPECT_EQ((SourceLocation{"a.csg", 3, 0}.str()), "a.csg:3");
}
