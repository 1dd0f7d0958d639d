#include "servo/servo_gain.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::servo {
void ServoGain::Validate() const {
  control::RequirePositive(at_zero_per_s, "ServoGain.at_zero_per_s");
  control::RequirePositive(at_infinity_per_s, "ServoGain.at_infinity_per_s");
  control::RequirePositive(slope_at_zero_per_s, "ServoGain.slope_at_zero_per_s");
  if (at_infinity_per_s > at_zero_per_s) {
    throw std::invalid_argument(
        "ServoGain.at_infinity_per_s = " + std::to_string(at_infinity_per_s) +
        " exceeds at_zero_per_s = " + std::to_string(at_zero_per_s) +
        "; set them equal for a constant gain");
  }
}

}  // namespace aperture::servo
