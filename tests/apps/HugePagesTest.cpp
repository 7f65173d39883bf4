// When strata-render and strata-view run themselves again with glibc's
// huge-page tunable (apps/common/HugePages.h).

#include <gtest/gtest.h>

#include "HugePages.h"

namespace {

using strata::apps::tunablesForHugePages;

constexpr const char* kMadvise = "always [madvise] never";

TEST(HugePages, AddedWhereTheKernelGivesThemOnRequest) {
    EXPECT_EQ(tunablesForHugePages(nullptr, kMadvise), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(tunablesForHugePages("", kMadvise), "glibc.malloc.hugetlb=1");
    // A user's other tunables are kept, in their order.
    EXPECT_EQ(tunablesForHugePages("glibc.malloc.arena_max=2", kMadvise),
              "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
}

TEST(HugePages, LeftAloneWhereTheKernelDecidesOrTheUserHas) {
    EXPECT_EQ(tunablesForHugePages(nullptr, "[always] madvise never"), std::nullopt);
    EXPECT_EQ(tunablesForHugePages(nullptr, "always madvise [never]"), std::nullopt);
    EXPECT_EQ(tunablesForHugePages(nullptr, ""), std::nullopt);  // no such file: no THP
    // The user's choice, either way, and the program run again: never twice.
    EXPECT_EQ(tunablesForHugePages("glibc.malloc.hugetlb=0", kMadvise), std::nullopt);
    EXPECT_EQ(tunablesForHugePages("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1", kMadvise), std::nullopt);
}

}  // namespace
