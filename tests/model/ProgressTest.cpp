// Progress and cancellation of long CPU work (strata/core/Progress.h) as the
// geometry reports it: every step counted against a total that it never
// passes, and a cancel honoured at the next step without a half result kept.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "strata/core/Progress.h"
#include "strata/exact/Exact.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;

namespace {

struct Report {
    std::string what;
    std::size_t done, total;
};

// Records every report; asks to stop once it hears of step `stopAt` of `stopWhat`.
class Recorder : public Progress {
public:
    Recorder() = default;
    Recorder(std::string stopWhat, std::size_t stopAt) : stopWhat_(std::move(stopWhat)), stopAt_(stopAt) {}
    void update(const char* what, std::size_t done, std::size_t total) override {
        reports.push_back({what, done, total});
        if (!stopWhat_.empty() && stopWhat_ == what && done == stopAt_) stop_ = true;
    }
    bool cancelled() const override { return stop_; }
    std::vector<Report> reports;

private:
    std::string stopWhat_;
    std::size_t stopAt_ = 0;
    bool stop_ = false;
};

// A hull of a difference: the difference is evaluated exactly (two
// booleans: the balls overlap, so they cannot be taken away together).
scene::Tree exactScene(double size) {
    std::istringstream in("hull() { difference() { cube(size = " + std::to_string(size) +
                          "); sphere(r = 1); multmatrix([[1, 0, 0, 1.5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) "
                          "sphere(r = 1); } }\n");
    return scene::parseCsg(in, "progress.csg", ".");
}

TEST(Progress, ExactWorkReportsEachBooleanOfItsTotal) {
    const scene::Tree tree = exactScene(3.25);
    Recorder recorder;
    {
        const ProgressScope scope(&recorder);
        model::buildModel(tree);
    }
    std::size_t booleans = 0;
    for (const Report& r : recorder.reports) {
        EXPECT_LT(r.done, r.total) << r.what;
        if (r.what == "exact difference") {
            EXPECT_EQ(r.done, booleans++);
            EXPECT_EQ(r.total, 2u);
        }
    }
    EXPECT_EQ(booleans, 2u);
    // Without a sink nothing is reported, and nothing is in the way.
    EXPECT_NO_THROW(model::buildModel(exactScene(3.5)));
}

TEST(Progress, CancelStopsAtTheNextStepAndKeepsNoResult) {
    const scene::Tree tree = exactScene(3.75);
    Recorder first("exact difference", 1);  // stops before the second boolean
    {
        const ProgressScope scope(&first);
        EXPECT_THROW(model::buildModel(tree), Cancelled);
    }
    ASSERT_FALSE(first.reports.empty());
    EXPECT_EQ(first.reports.back().what, "exact difference");
    EXPECT_EQ(first.reports.back().done, 1u);
    // The cancelled evaluation cached nothing: the next one does the work.
    const std::size_t hits = exact::exactCacheHits();
    Recorder second;
    {
        const ProgressScope scope(&second);
        model::buildModel(tree);
    }
    EXPECT_EQ(exact::exactCacheHits(), hits);
    std::size_t booleans = 0;
    for (const Report& r : second.reports) booleans += r.what == "exact difference";
    EXPECT_EQ(booleans, 2u);
}

TEST(Progress, ScopesNestAndRestore) {
    Recorder outer, inner;
    {
        const ProgressScope a(&outer);
        {
            const ProgressScope b(&inner);
            reportProgress("inner", 0, 1);
        }
        reportProgress("outer", 0, 1);
        {
            const ProgressScope none(nullptr);
            reportProgress("nobody", 0, 1);
        }
    }
    reportProgress("after", 0, 1);
    ASSERT_EQ(inner.reports.size(), 1u);
    EXPECT_EQ(inner.reports[0].what, "inner");
    ASSERT_EQ(outer.reports.size(), 1u);
    EXPECT_EQ(outer.reports[0].what, "outer");
}

}  // namespace
