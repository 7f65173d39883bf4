#pragma once
// Progress and cancellation of long CPU work: exact evaluation of subtrees,
// minkowski sums of non-convex solids, meshing many leaves. The work reports
// its steps to the sink installed on its own thread; a program shows them
// (strata-render on a terminal, strata-view in its panel) and may ask the
// work to stop, which it does at its next step by throwing Cancelled.
//
// A step is as fine as the libraries allow: one exact boolean, one convex
// decomposition, one leaf. A single step is never interrupted.

#include <cstddef>
#include <exception>

namespace strata {

// Thrown by reportProgress when the sink asks to stop. Not a strata::Error:
// it is no mistake in the input, and handlers that name an input position
// let it pass.
class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return "cancelled"; }
};

class Progress {
public:
    virtual ~Progress() = default;
    // `what` names the work ("exact difference", "minkowski: convex parts");
    // `done` of `total` steps are finished (total 0: unknown). Called on the
    // working thread, often: keep it cheap.
    virtual void update(const char* what, std::size_t done, std::size_t total) = 0;
    // Whether the work should stop at its next step.
    virtual bool cancelled() const { return false; }
};

// Installs `sink` for the calling thread's work while it lives (nullptr: none),
// restoring the one before it.
class ProgressScope {
public:
    explicit ProgressScope(Progress* sink);
    ~ProgressScope();
    ProgressScope(const ProgressScope&) = delete;
    ProgressScope& operator=(const ProgressScope&) = delete;

private:
    Progress* previous_;
};

// Tells this thread's sink, if any, that `done` of `total` steps of `what`
// are finished; throws Cancelled if it asks to stop.
void reportProgress(const char* what, std::size_t done, std::size_t total);

}  // namespace strata
