#pragma once
// One sample of a flat-output reference trajectory (Faessler thesis F.4): the position of the
// centre of mass in W with its derivatives up to snap, and the heading psi with two derivatives.
// The heading is the angle of x_C = [cos psi, sin psi, 0] (F.9): the projection of x_B onto the
// x_W-y_W plane is kept collinear with x_C (F.11). Units SI, angles in radians.
#include <Eigen/Core>
#include <cmath>

namespace aperture::control {

struct TrajectoryPoint {
  double t_s = 0.0;                               // time of the sample [s]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // position [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // velocity [m/s]
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();  // acceleration [m/s^2]
  Eigen::Vector3d j_W = Eigen::Vector3d::Zero();  // jerk [m/s^3]
  Eigen::Vector3d s_W = Eigen::Vector3d::Zero();  // snap [m/s^4]
  double heading_rad = 0.0;                       // psi [rad]
  double heading_rate_radps = 0.0;                // psi dot [rad/s]
  double heading_acc_radps2 = 0.0;                // psi ddot [rad/s^2]

  // True when every member is finite.
  bool IsFinite() const {
    return std::isfinite(t_s) && p_W.allFinite() && v_W.allFinite() && a_W.allFinite() &&
           j_W.allFinite() && s_W.allFinite() && std::isfinite(heading_rad) &&
           std::isfinite(heading_rate_radps) && std::isfinite(heading_acc_radps2);
  }
};

}  // namespace aperture::control
