#pragma once
// Gain lambda of the visual-servo law v = -lambda (L J)^+ (s - s*) (Chaumette & Hutchinson, IEEE
// RAM 2006, the exponential decrease of the error), adaptive as ViSP's vpAdaptiveGain:
//   lambda(x) = (at_zero - at_infinity) exp(-slope_at_zero / (at_zero - at_infinity) * x)
//               + at_infinity,   x = |s - s*|_inf,
// high near convergence (fast final approach), low for large errors (no violent first step).
// at_zero == at_infinity gives a constant gain (slope_at_zero is then unused).
namespace aperture::servo {

struct ServoGain {
  // Defaults of ViSP's drone servo examples (Bebop 2, Pixhawk IBVS): 1.5 near zero error,
  // 0.7 for large errors, slope 30 at zero [1/s].
  double at_zero_per_s = 1.5;
  double at_infinity_per_s = 0.7;
  double slope_at_zero_per_s = 30.0;

  // Throws std::invalid_argument naming the field when a gain is not finite or not positive, or
  // at_infinity exceeds at_zero (the gain must not grow with the error).
  void Validate() const;
};

}  // namespace aperture::servo
