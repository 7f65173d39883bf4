#pragma once
// Wall time in milliseconds on the steady clock, as every figure strata
// prints is taken.

#include <chrono>

namespace strata {

inline double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace strata
