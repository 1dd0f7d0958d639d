#pragma once
// What every servo law hands the flatness/position controller: a velocity reference of the body
// origin in B and a yaw rate (the 4 degrees of freedom a quadrotor commands directly; roll and
// pitch are the controller's means of producing the velocity, not references).
//
// A camera twist [v_C; omega_C] (velocity of the camera origin and angular velocity, both
// expressed in C) maps to the body through the camera mount T_BC (p_B = T_BC * p_C) as a rigid
// body: omega_B = R_BC omega_C and v_B = R_BC v_C + p_BC x omega_B (the body origin sits at
// -p_BC from the camera). This is ViSP's velocity twist matrix bVc of bMc = T_BC; the servo
// laws build the reverse map cVe from T_CB (ViSP's cMe) for their 4-DOF vehicle Jacobian.
//
//   BodyVelocityFromCameraTwist(twist_C, T_BC)   valid: the twist of C, the mount of C on B
//   BodyVelocityFromCameraTwist(twist_C, T_CB)   invalid: maps with the inverse mount
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <iosfwd>

namespace aperture::servo {

// [v (m/s); omega (rad/s)], both expressed in the frame named by the variable (twist_C).
using Twist = Eigen::Matrix<double, 6, 1>;

struct BodyVelocityReference {
  Eigen::Vector3d v_B = Eigen::Vector3d::Zero();  // velocity of the body origin, in B [m/s]
  double yaw_rate_radps = 0.0;                    // rotation rate about z_B [rad/s]
};
std::ostream& operator<<(std::ostream& os, const BodyVelocityReference& reference);

// 6x6 twist transform of T_AB: twist_A = VelocityTwistMatrix(T_AB) * twist_B for frames A and B
// on one rigid body, [R_AB, [p_AB]x R_AB; 0, R_AB] (ViSP's vpVelocityTwistMatrix(aMb)).
Eigen::Matrix<double, 6, 6> VelocityTwistMatrix(const Eigen::Isometry3d& T_AB);

// The body twist of the camera twist (see above), reduced to the 4 commanded DOFs: v_B and the
// z_B component of omega_B. The roll and pitch rates the twist may ask for are dropped.
// Throws std::invalid_argument when the twist or the mount is not finite.
BodyVelocityReference BodyVelocityFromCameraTwist(const Twist& twist_C,
                                                  const Eigen::Isometry3d& T_BC);

// The camera twist [v_C; omega_C] of the body moving with `reference` (zero roll and pitch
// rates): VelocityTwistMatrix(T_BC^-1) applied to [v_B; 0, 0, yaw rate]. The inverse of
// BodyVelocityFromCameraTwist on twists without roll and pitch rates.
Twist CameraTwistFromBodyVelocity(const BodyVelocityReference& reference,
                                  const Eigen::Isometry3d& T_BC);

// Throws std::invalid_argument, prefixed by `who`, unless T_BC is finite with an orthonormal
// rotation of determinant +1 (tolerance 1e-6 on R^T R - I).
void RequireRigidMount(const Eigen::Isometry3d& T_BC, const char* who);

}  // namespace aperture::servo
