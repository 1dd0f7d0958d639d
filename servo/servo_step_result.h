#pragma once
// One step of a servo law: its status, the body velocity reference, the camera twist that
// reference moves the camera with, and the feature error the law drove.
#include <Eigen/Core>
#include <iosfwd>

#include "servo/body_velocity_reference.h"

namespace aperture::servo {

enum class ServoStatus {
  kOk,
  // The features are not defined on this input (polygon of ~zero area, orientation of a polygon
  // whose second moments are isotropic): the reference is zero, the caller decides (hover, abort).
  kDegenerateFeatures,
};
// "ok", "degenerate_features".
const char* ToString(ServoStatus status);

struct ServoStepResult {
  ServoStatus status = ServoStatus::kOk;
  BodyVelocityReference reference;            // to the position controller
  Twist twist_C = Twist::Zero();              // camera twist of `reference` (rigid mount)
  Eigen::VectorXd error = Eigen::VectorXd();  // s - s*, order given by the law's header
  double error_norm = 0.0;                    // |s - s*|_2 (features are not of one unit)
};
std::ostream& operator<<(std::ostream& os, const ServoStepResult& result);

}  // namespace aperture::servo
