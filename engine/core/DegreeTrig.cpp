#include "strata/core/DegreeTrig.h"

#include <cmath>
#include <limits>

namespace strata {
namespace {

// Past this the reduction to one turn has no significant bits left.
constexpr double kHugeDegrees = double(1L << 26) * 360.0 * double(1L << 26);

// Brings x into [0, 360); NaN when it cannot be reduced meaningfully.
// Angles already in range are left untouched, so they stay exact.
double reduceToTurn(double x) {
    if (x >= 0.0 && x < 360.0) return x;
    if (x < kHugeDegrees && x > -kHugeDegrees) return x - 360.0 * std::floor(x / 360.0);
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double sinDegrees(double degrees) {
    double x = reduceToTurn(degrees);
    if (std::isnan(x)) return x;
    const bool negate = x >= 180.0;
    if (negate) x -= 180.0;
    if (x > 90.0) x = 180.0 - x;  // sin(180 - a) = sin(a)
    double s;
    if (x < 45.0) {
        s = x == 30.0 ? 0.5 : std::sin(x * kDegToRad);
    } else if (x == 45.0) {
        s = 0.70710678118654752440;  // M_SQRT1_2
    } else if (x == 60.0) {
        s = kSqrtThreeQuarters;
    } else {
        s = std::cos((90.0 - x) * kDegToRad);  // exact 1 at 90
    }
    return negate ? -s : s;
}

double cosDegrees(double degrees) {
    double x = reduceToTurn(degrees);
    if (std::isnan(x)) return x;
    bool negate = x >= 180.0;
    if (negate) x -= 180.0;
    if (x > 90.0) {  // cos(180 - a) = -cos(a)
        x = 180.0 - x;
        negate = !negate;
    }
    double c;
    if (x > 45.0) {
        c = x == 60.0 ? 0.5 : std::sin((90.0 - x) * kDegToRad);  // exact 0 at 90
    } else if (x == 45.0) {
        c = 0.70710678118654752440;
    } else if (x == 30.0) {
        c = kSqrtThreeQuarters;
    } else {
        c = std::cos(x * kDegToRad);
    }
    return negate ? -c : c;
}

}  // namespace strata
