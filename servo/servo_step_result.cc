#include "servo/servo_step_result.h"

#include <ostream>

namespace aperture::servo {

const char* ToString(ServoStatus status) {
  switch (status) {
    case ServoStatus::kOk:
      return "ok";
    case ServoStatus::kDegenerateFeatures:
      return "degenerate_features";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& os, const ServoStepResult& result) {
  return os << "servo step: " << ToString(result.status) << ", |e| " << result.error_norm << ", "
            << result.reference;
}

}  // namespace aperture::servo
