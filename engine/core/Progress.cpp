#include "strata/core/Progress.h"

namespace strata {
namespace {

thread_local Progress* current = nullptr;

}  // namespace

ProgressScope::ProgressScope(Progress* sink) : previous_(current) { current = sink; }

ProgressScope::~ProgressScope() { current = previous_; }

void reportProgress(const char* what, std::size_t done, std::size_t total) {
    if (current == nullptr) return;
    current->update(what, done, total);
    if (current->cancelled()) throw Cancelled();
}

}  // namespace strata
