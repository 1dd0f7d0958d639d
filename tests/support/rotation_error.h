#pragma once
// Test support: the angle [deg] of the rotation between the orientations of two poses, |log(R_a^T
// R_b)|, the orientation error the pose tests bound.
#include <Eigen/Geometry>

#include "control/constants.h"
#include "control/so3.h"

namespace aperture::test_support {

inline double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return control::LogSo3(a.linear().transpose() * b.linear()).norm() * control::kRadToDeg;
}

}  // namespace aperture::test_support
