#pragma once
// Quaternion attitude controller of Faessler thesis paper B (B.10)-(B.20), used for the feedback
// body rates omega_fb of (F.37) (F cites it as [37]). It is split so that roll/pitch have
// priority over yaw:
//  * roll/pitch (B.10)-(B.15): the shortest rotation q_e,RP taking the current body z axis onto
//    the desired thrust direction z_des; [p, q]_des = +-2 p_rp q_e,RP^(x,y). It never commands a
//    rotation about z_B, and the tilt error obeys alpha' = -2 p_rp sin(alpha/2) whatever the yaw
//    gain or heading error (tan(alpha/4) decays as exp(-p_rp t) under perfect rate tracking).
//  * yaw (B.16)-(B.20): the remaining rotation q_e,y about z_des from the tilted attitude to the
//    full desired attitude built from z_des and the heading psi; r_des = +-2 p_yaw q_e,y^(z).
//
// Desired attitude (B.16)-(B.19), identical to (F.33)-(F.35) and to (F.11)-(F.13) for a
// drag-free reference: x_des = y_C x z_des / |y_C x z_des|, y_des = z_des x x_des, with the B.18
// text's negation of x_des when z_des points downwards (z_des^z < 0): then y_C x z_des projects
// onto -x_C, and the negation keeps the horizontal projection of x_des on the side of x_C, so the
// heading psi means the same for an inverted vehicle (the recovery's throws). (F.11) does not
// negate: for a reference whose thrust points downwards R_des is R_ref turned by pi about z_des.
//
// Special cases: z_B antiparallel to z_des (alpha = pi) makes the axis of (B.12) undefined; the
// controller then rotates about the body x axis. When |y_C x z_des| < kYawSingularity the heading
// is undefined: r_des = 0 (B.18 text), R_des uses x_C made orthogonal to z_des, and
// heading_defined is false.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aperture::control {

struct AttitudeControllerGains {
  double p_rp_per_s = 16.6;  // roll/pitch attitude gain p_rp (Table A.2)
  double p_yaw_per_s = 5.0;  // yaw attitude gain p_yaw (Table A.2)
  // Throws std::invalid_argument naming the gain when it is negative or not finite.
  void Validate() const;
};

struct AttitudeFeedback {
  Eigen::Vector3d omega_fb_B = Eigen::Vector3d::Zero();    // [p, q, r]_des [rad/s]
  Eigen::Matrix3d R_des_WB = Eigen::Matrix3d::Identity();  // (B.16)-(B.19)
  double tilt_error_rad = 0.0;                             // alpha of (B.11)
  bool heading_defined = true;
};

// Desired attitude of (B.16)-(B.19) / (F.33)-(F.35) for a unit thrust direction z_des_W.
// `heading_defined` (optional) receives false in the heading singularity.
Eigen::Matrix3d ComputeDesiredAttitude(const Eigen::Vector3d& z_des_W, double heading_rad,
                                       bool* heading_defined = nullptr);

class AttitudeController {
 public:
  explicit AttitudeController(const AttitudeControllerGains& gains = {});
  // q_WB: current attitude; z_des_W: desired thrust direction (normalized inside; must be
  // non-zero and finite, else std::invalid_argument); heading_rad: psi_ref.
  AttitudeFeedback Compute(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& z_des_W,
                           double heading_rad) const;
  const AttitudeControllerGains& gains() const { return gains_; }

 private:
  AttitudeControllerGains gains_;
};

}  // namespace aperture::control
