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

TEST(Error, RethrowNamesAPositionOnce) {
    auto rethrown = [](const SourceLocation& where, const Error& e) -> std::string {
        try {
            strata::rethrowAt(where, e);
        } catch (const Error& again) {
            return again.what();
        }
        return "";
    };
    // An error with no position in the file is named by the node.
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error("hull: too many points")), "a.csg:3:1: hull: too many points");
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error(SourceLocation{"m.stl", 0, 0}, "not closed")), "a.csg:3:1: m.stl: not closed");
    // One raised where no position was known (a helper given an empty
    // location) takes the node's in place of "<input>".
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error(SourceLocation{}, "not closed")), "a.csg:3:1: not closed");
    // One a node inside it named already keeps its own position only.
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error(SourceLocation{"a.csg", 9, 4}, "bad")), "a.csg:9:4: bad");
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error(SourceLocation{"a.csg", 3, 1}, "bad")), "a.csg:3:1: bad");
    // A file of another name that starts the same is another file.
    EXPECT_EQ(rethrown({"a.csg", 3, 1}, Error(SourceLocation{"a.csg.bak", 2, 2}, "bad")), "a.csg:3:1: a.csg.bak:2:2: bad");
}

TEST(Error, ControlBytesAreWrittenAsEscapes) {
    EXPECT_EQ(strata::printable("a\x1b]0;title\x07z"), "a\\x1b]0;title\\x07z");
    EXPECT_EQ(strata::printable("line\nnext\x7f"), "line\\x0anext\\x7f");
    // UTF-8 and backslashes pass as they are, so escaping twice changes nothing.
    EXPECT_EQ(strata::printable("caf\xc3\xa9 \\x1b"), "caf\xc3\xa9 \\x1b");
    EXPECT_EQ(strata::printable(strata::printable("\x1b")), "\\x1b");
    // A file name in a location, and a message quoting one, stay one line
    // with no byte a terminal would act on.
    const Error e(SourceLocation{"a\x1b[31m.csg", 2, 3}, "import cannot read 'b\nc.stl'");
    EXPECT_STREQ(e.what(), "a\\x1b[31m.csg:2:3: import cannot read 'b\\x0ac.stl'");
    EXPECT_STREQ(Error("x\ty").what(), "x\\x09y");
}
