#include "servo/servo_gain.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::servo {
namespace {

void RequirePositive(double value, const char* name) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument(std::string("ServoGain.") + name + " = " + std::to_string(value) +
                                " must be finite and > 0 [1/s]");
  }
}

}  // namespace

void ServoGain::Validate() const {
  RequirePositive(at_zero_per_s, "at_zero_per_s");
  RequirePositive(at_infinity_per_s, "at_infinity_per_s");
  RequirePositive(slope_at_zero_per_s, "slope_at_zero_per_s");
  if (at_infinity_per_s > at_zero_per_s) {
    throw std::invalid_argument(
        "ServoGain.at_infinity_per_s = " + std::to_string(at_infinity_per_s) +
        " exceeds at_zero_per_s = " + std::to_string(at_zero_per_s) +
        "; set them equal for a constant gain");
  }
}

}  // namespace aperture::servo
