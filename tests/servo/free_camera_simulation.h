#pragma once
// Test support: a camera flying as a level quadrotor in ViSP's vpSimulatorCamera (the "free
// camera" of ViSP's servo examples). The servo laws' camera twists carry no roll or pitch rate,
// so the simulated body stays level; vpSimulatorCamera integrates each twist over one sampling
// period by the SE(3) exponential map.
#include <visp3/robot/vpSimulatorCamera.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "servo/body_velocity_reference.h"
#include "servo/internal/visp_conversions.h"

namespace aperture::servo::testing {

class FreeCameraSimulation {
 public:
  FreeCameraSimulation(const Eigen::Isometry3d& T_WC, double dt_s) {
    camera_.setSamplingTime(dt_s);
    // vpRobot saturates at 0.2 m/s and 0.7 rad/s by default; the laws' own gains bound the speed.
    camera_.setMaxTranslationVelocity(100.0);
    camera_.setMaxRotationVelocity(100.0);
    camera_.setPosition(internal::ToVisp(T_WC));
  }

  void Apply(const Twist& twist_C) {
    vpColVector v(6);
    for (int i = 0; i < 6; ++i) v[i] = twist_C[i];
    camera_.setVelocity(vpRobot::CAMERA_FRAME, v);
  }

  Eigen::Isometry3d T_WC() const { return internal::FromVisp(camera_.getPosition()); }

  // Normalized image coordinates (x = X/Z, y = Y/Z in C) of world points.
  std::vector<Eigen::Vector2d> Project(const std::vector<Eigen::Vector3d>& points_W) const {
    const Eigen::Isometry3d T_CW = T_WC().inverse();
    std::vector<Eigen::Vector2d> image;
    for (const Eigen::Vector3d& p_W : points_W) {
      const Eigen::Vector3d p_C = T_CW * p_W;
      image.emplace_back(p_C.x() / p_C.z(), p_C.y() / p_C.z());
    }
    return image;
  }

 private:
  vpSimulatorCamera camera_;
};

// Body pose at p_W with heading yaw_rad (level).
inline Eigen::Isometry3d LevelPose(const Eigen::Vector3d& p_W, double yaw_rad) {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WB.translation() = p_W;
  return T_WB;
}

// Forward camera (x_C = -y_B, y_C = -z_B, z_C = x_B), 0.1 m ahead of the body origin.
inline Eigen::Isometry3d ForwardCameraMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() << 0, 0, 1,  //
      -1, 0, 0,              //
      0, -1, 0;
  T_BC.translation() = Eigen::Vector3d(0.1, 0.0, 0.0);
  return T_BC;
}

// Downward camera (x_C = -y_B, y_C = -x_B, z_C = -z_B), 5 cm below the body origin.
inline Eigen::Isometry3d DownwardCameraMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() << 0, -1, 0,  //
      -1, 0, 0,               //
      0, 0, -1;
  T_BC.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
  return T_BC;
}

}  // namespace aperture::servo::testing
