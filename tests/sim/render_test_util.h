#pragma once
// Shared fixtures of the sim renderer tests: the two test cameras and pose helpers.
#include <Eigen/Geometry>
#include <memory>

#include "perception/camera/equidistant_camera.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::sim::testing {

// 752 x 480 pinhole, ~84 deg horizontal field of view.
inline std::unique_ptr<perception::CameraModel> MakeTestPinhole() {
  return std::make_unique<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
}

// 752 x 480 equidistant fisheye seeing 180 deg horizontally: theta = 90 deg maps to
// 215 * theta_d(pi/2) = 327 px from the centre (< 376 px half width).
inline std::unique_ptr<perception::CameraModel> MakeTestFisheye() {
  return std::make_unique<perception::EquidistantCamera>(
      752, 480, perception::PinholeIntrinsics{215.0, 215.0, 375.5, 239.5},
      perception::EquidistantDistortion{-0.02, 0.003, 0.0, 0.0});
}

// Pose of a camera at p_WC looking along forward_W with image-down roughly along -z_W.
inline Eigen::Isometry3d LookAt(const Eigen::Vector3d& p_WC, const Eigen::Vector3d& forward_W) {
  const Eigen::Vector3d z = forward_W.normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear().col(0) = x;
  T_WC.linear().col(1) = y;
  T_WC.linear().col(2) = z;
  T_WC.translation() = p_WC;
  return T_WC;
}

inline Eigen::Isometry3d Pose(const Eigen::Vector3d& rotation_vector, const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (rotation_vector.norm() > 0.0) {
    T.linear() = Eigen::AngleAxisd(rotation_vector.norm(), rotation_vector.normalized()).toRotationMatrix();
  }
  T.translation() = p;
  return T;
}

}  // namespace aperture::sim::testing
