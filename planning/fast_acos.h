#pragma once
// acos without libm's call: the approach planner evaluates one view angle (9) per trajectory
// sample, a million candidates per second, and std::acos was half of that time. Accurate to
// 4.5e-16 rad (1 ulp of pi) over [-1, 1] (tests/planning/fast_acos_test.cc checks it against
// long-double acos). Arguments outside [-1, 1] are clamped; NaN gives NaN.
//
// Method (as fdlibm's acos): one polynomial kernel for asin on [0, 0.5],
//   asin(s) = s + s^3 P(s^2),
// used directly for |x| <= 0.5 (acos x = pi/2 - asin x) and through the half-angle identity
// acos|x| = 2 asin(sqrt((1 - |x|) / 2)) above. P is the degree-11 Chebyshev interpolant of
// (asin(sqrt z) - sqrt z) / z^1.5 on z in [0, 0.25], computed in long double from the series.
#include <algorithm>
#include <cmath>

namespace aperture::planning {

inline double FastAcos(double x) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr double kP[12] = {0.16666666666666649,   0.075000000000207553,  0.044642857103434207,
                             0.030381947366548478,  0.022372047646690582,  0.0173552597163108,
                             0.013929655317884482,  0.011875478578531329,  0.0078030165832387866,
                             0.016035335582273547,  -0.010748778469860554, 0.028169037774205208};
  const double ax = std::fabs(x);
  const bool small = ax <= 0.5;
  const double z = small ? x * x : 0.5 * (1.0 - std::min(ax, 1.0));  // std::min keeps NaN
  const double s = small ? x : std::sqrt(z);
  // Estrin's scheme: depth 4 instead of Horner's 11 dependent multiply-adds.
  const double z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const double p = ((kP[0] + kP[1] * z) + (kP[2] + kP[3] * z) * z2) +
                   ((kP[4] + kP[5] * z) + (kP[6] + kP[7] * z) * z2) * z4 +
                   ((kP[8] + kP[9] * z) + (kP[10] + kP[11] * z) * z2) * z8;
  const double asin_s = s + s * z * p;
  if (small) return 0.5 * kPi - asin_s;
  return x > 0.0 ? 2.0 * asin_s : kPi - 2.0 * asin_s;
}

}  // namespace aperture::planning
