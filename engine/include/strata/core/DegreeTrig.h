#pragma once
// Sine and cosine of an angle in degrees, following OpenSCAD 2021.01's rules
// (src/degree_trig.cc) so that tessellated vertices match it bit for bit:
// the angle is reduced to [0, 90] by symmetry, 30, 45, 60 and 90 degrees give
// exact table values (0.5, sqrt(1/2), sqrt(3/4), 1), angles at or above 45 are
// computed as the cosine (sine) of the complement, and angles beyond about
// 2^52 degrees give NaN.

namespace strata {

inline constexpr double kSqrtThreeQuarters = 0.86602540378443859659;  // sqrt(3)/2, OpenSCAD's M_SQRT3_4
inline constexpr double kDegToRad = 0.017453292519943295769;          // pi/180, OpenSCAD's M_DEG2RAD

double sinDegrees(double degrees);
double cosDegrees(double degrees);

}  // namespace strata
