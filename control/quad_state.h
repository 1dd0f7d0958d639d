#pragma once
// Rigid-body state of the quadrotor. Frames (DESIGN.md): W world (z up), B body (x forward, y left,
// z up; the IMU frame). Units SI.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aperture::control {

struct QuadState {
  double t_s = 0.0;                                           // time of the state [s]
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();             // origin of B in W [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();              // velocity of B in W [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();   // rotation B -> W
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();          // body rates in B [rad/s]

  // True when every component is finite and q_WB has unit norm (|1 - |q|| < 1e-6).
  bool IsValid() const;
};

}  // namespace aperture::control
