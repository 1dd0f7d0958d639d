#include "control/attitude_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace aperture::control {
namespace {

// Rotation of the exact exponential map for body rates held over dt (F.3 with omega constant).
Eigen::Quaterniond Integrate(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega_B,
                             double dt) {
  const double angle = omega_B.norm() * dt;
  if (angle == 0.0) return q;
  return (q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega_B.normalized()))).normalized();
}

double AngleBetween(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(A.transpose() * B).angle();
}

struct AttitudeLoopRun {
  std::vector<double> tilt_rad;  // alpha of (B.11) per step
  std::vector<double> full_rad;  // angle between R and R_des per step
  Eigen::Quaterniond final_q;
};

// Kinematic closed loop: the body follows the commanded rates exactly (perfect inner loop).
AttitudeLoopRun SimulateAttitudeLoop(const AttitudeControllerGains& gains,
                                     const Eigen::Quaterniond& q0, const Eigen::Vector3d& z_des,
                                     double heading, double duration_s, double dt) {
  const AttitudeController controller(gains);
  AttitudeLoopRun run;
  Eigen::Quaterniond q = q0;
  for (double t = 0.0; t < duration_s; t += dt) {
    const AttitudeFeedback fb = controller.Compute(q, z_des, heading);
    run.tilt_rad.push_back(fb.tilt_error_rad);
    run.full_rad.push_back(AngleBetween(q.toRotationMatrix(), fb.R_des_WB));
    q = Integrate(q, fb.omega_fb_B, dt);
  }
  run.final_q = q;
  return run;
}

// Large initial error: 112 deg of tilt and a heading far off.
const Eigen::Quaterniond kStart(Eigen::AngleAxisd(2.3, Eigen::Vector3d(1, 2, 0).normalized()) *
                                Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()));
const Eigen::Vector3d kZDes = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
constexpr double kHeading = 1.5;
constexpr double kAttitudeLoopDt_s = 1e-4;

TEST(AttitudeControllerTest, TiltErrorFollowsAnalyticDecayOfB15) {
  const AttitudeControllerGains gains;
  const AttitudeLoopRun run =
      SimulateAttitudeLoop(gains, kStart, kZDes, kHeading, 1.0, kAttitudeLoopDt_s);
  ASSERT_GT(run.tilt_rad.front(), 1.9);
  // alpha' = -2 p_rp sin(alpha/2)  =>  tan(alpha/4) = tan(alpha0/4) exp(-p_rp t).
  double max_error = 0.0;
  for (size_t k = 0; k < run.tilt_rad.size(); ++k) {
    const double t = k * kAttitudeLoopDt_s;
    const double exact =
        4.0 * std::atan(std::tan(run.tilt_rad.front() / 4.0) * std::exp(-gains.p_rp_per_s * t));
    max_error = std::max(max_error, std::abs(run.tilt_rad[k] - exact));
  }
  // Zero-order hold of the rates over 1e-4 s: first-order error ~ p_rp dt alpha ~ 4e-3 rad
  // at most, accumulated while alpha decays.
  EXPECT_LT(max_error, 5e-3);
}

TEST(AttitudeControllerTest, RollPitchHasPriorityAndIsDecoupledFromYaw) {
  AttitudeControllerGains no_yaw;
  no_yaw.p_yaw_per_s = 0.0;
  const AttitudeLoopRun with_yaw = SimulateAttitudeLoop(AttitudeControllerGains{}, kStart, kZDes,
                                                        kHeading, 1.0, kAttitudeLoopDt_s);
  const AttitudeLoopRun without_yaw =
      SimulateAttitudeLoop(no_yaw, kStart, kZDes, kHeading, 1.0, kAttitudeLoopDt_s);
  double max_difference = 0.0;
  for (size_t k = 0; k < with_yaw.tilt_rad.size(); ++k) {
    max_difference =
        std::max(max_difference, std::abs(with_yaw.tilt_rad[k] - without_yaw.tilt_rad[k]));
  }
  // Exactly equal in continuous time (yaw rate never moves z_B); the held-rate discretization
  // couples them at O(dt).
  EXPECT_LT(max_difference, 2e-3);
  // After 0.25 s the tilt (gain 16.6) is nearly gone while the heading (gain 5) is not.
  const size_t k = static_cast<size_t>(0.25 / kAttitudeLoopDt_s);
  EXPECT_LT(with_yaw.tilt_rad[k], 0.05 * with_yaw.tilt_rad.front());
  EXPECT_GT(with_yaw.full_rad[k], 0.2 * with_yaw.full_rad.front());
  // The roll/pitch command does not depend on the heading at all.
  const AttitudeController controller;
  const Eigen::Vector3d a = controller.Compute(kStart, kZDes, 0.0).omega_fb_B;
  const Eigen::Vector3d b = controller.Compute(kStart, kZDes, 2.0).omega_fb_B;
  EXPECT_EQ(a.head<2>(), b.head<2>());
  EXPECT_NE(a.z(), b.z());
}

TEST(AttitudeControllerTest, ConvergesToFullDesiredAttitudeFromLargeError) {
  for (const Eigen::Quaterniond& start :
       {kStart, Eigen::Quaterniond(Eigen::AngleAxisd(kHeading + 3.0, Eigen::Vector3d::UnitZ())),
        Eigen::Quaterniond(Eigen::AngleAxisd(2.9, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()))}) {
    const AttitudeLoopRun run =
        SimulateAttitudeLoop(AttitudeControllerGains{}, start, kZDes, kHeading, 4.0, 1e-3);
    EXPECT_GT(run.full_rad.front(), 1.9);  // more than 110 deg away
    // Yaw decays like exp(-5 t): 4 s leaves ~1e-8 of the initial error.
    EXPECT_LT(run.full_rad.back(), 1e-6);
    EXPECT_LT(run.tilt_rad.back(), 1e-9);
  }
}

TEST(AttitudeControllerTest, DesiredAttitudeFollowsHeadingDefinition) {
  bool defined = false;
  const Eigen::Matrix3d R = ComputeDesiredAttitude(kZDes, kHeading, &defined);
  EXPECT_TRUE(defined);
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_LT((R.col(2) - kZDes).norm(), 1e-15);
  // (B.18): x_des lies in the plane of x_C and z_W, on the side of x_C.
  const Eigen::Vector3d x_C(std::cos(kHeading), std::sin(kHeading), 0.0);
  const Eigen::Vector3d y_C(-x_C.y(), x_C.x(), 0.0);
  EXPECT_NEAR(R.col(0).dot(y_C), 0.0, 1e-15);
  EXPECT_GT(R.col(0).dot(x_C), 0.0);
  // Level thrust: the desired attitude is the pure heading rotation.
  const Eigen::Matrix3d level = ComputeDesiredAttitude(Eigen::Vector3d::UnitZ(), kHeading);
  EXPECT_LT(
      (level - Eigen::AngleAxisd(kHeading, Eigen::Vector3d::UnitZ()).toRotationMatrix()).norm(),
      1e-15);
}

// B.18 text: when z_des points downwards, x_des is negated so that its horizontal projection
// still points along x_C (without it, y_C x z_des projects onto -x_C).
TEST(AttitudeControllerTest, DownwardThrustKeepsHeadingOnTheSideOfXc) {
  const Eigen::Vector3d x_C(std::cos(kHeading), std::sin(kHeading), 0.0);
  const Eigen::Vector3d y_C(-x_C.y(), x_C.x(), 0.0);
  for (const Eigen::Vector3d& z_des :
       {Eigen::Vector3d(0.3, -0.2, -1.0).normalized(),
        Eigen::Vector3d(-0.6, 0.1, -0.2).normalized(), Eigen::Vector3d(0.0, 0.0, -1.0)}) {
    bool defined = false;
    const Eigen::Matrix3d R = ComputeDesiredAttitude(z_des, kHeading, &defined);
    EXPECT_TRUE(defined);
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LT((R.col(2) - z_des).norm(), 1e-15);
    EXPECT_NEAR(R.col(0).dot(y_C), 0.0, 1e-15);
    EXPECT_GT(R.col(0).dot(x_C), 0.0) << z_des.transpose();
    // The un-negated axis of (B.18) points the other way.
    EXPECT_LT(y_C.cross(z_des).dot(x_C), 0.0);
  }
  // Upside down with thrust straight down: x_des = x_C, y_des = -y_C (a roll by pi of the
  // level attitude with heading psi).
  const Eigen::Matrix3d inverted = ComputeDesiredAttitude(-Eigen::Vector3d::UnitZ(), kHeading);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(kHeading, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_LT((inverted - expected).norm(), 1e-12);
  // A vehicle inverted at that attitude has no yaw error to correct.
  const AttitudeFeedback fb = AttitudeController{}.Compute(Eigen::Quaterniond(expected),
                                                           -Eigen::Vector3d::UnitZ(), kHeading);
  EXPECT_LT(fb.omega_fb_B.norm(), 1e-12);
}

TEST(AttitudeControllerTest, UpsideDownErrorRotatesAboutBodyX) {
  const AttitudeController controller;
  const AttitudeFeedback fb =
      controller.Compute(Eigen::Quaterniond::Identity(), -Eigen::Vector3d::UnitZ(), 0.0);
  EXPECT_TRUE(fb.omega_fb_B.allFinite());
  EXPECT_NEAR(fb.tilt_error_rad, M_PI, 1e-12);
  EXPECT_NEAR(fb.omega_fb_B.x(), 2.0 * 16.6, 1e-12);  // q_e,RP = (0, 1, 0, 0) in (B.15)
  EXPECT_NEAR(fb.omega_fb_B.y(), 0.0, 1e-12);
}

TEST(AttitudeControllerTest, HeadingSingularityCommandsNoYawRate) {
  const AttitudeController controller;
  // Thrust along y_C (heading 0): every rotation about z_des keeps x_B in the x_C-z_W plane.
  const AttitudeFeedback fb = controller.Compute(kStart, Eigen::Vector3d::UnitY(), 0.0);
  EXPECT_FALSE(fb.heading_defined);
  EXPECT_EQ(fb.omega_fb_B.z(), 0.0);
  EXPECT_TRUE(fb.omega_fb_B.allFinite());
  EXPECT_LT((fb.R_des_WB.transpose() * fb.R_des_WB - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(AttitudeControllerTest, ZeroErrorGivesZeroRates) {
  const Eigen::Quaterniond q(ComputeDesiredAttitude(kZDes, kHeading));
  const AttitudeFeedback fb = AttitudeController{}.Compute(q, kZDes, kHeading);
  EXPECT_LT(fb.omega_fb_B.norm(), 1e-12);
}

TEST(AttitudeControllerTest, InvalidGainsAndInputsThrow) {
  AttitudeControllerGains gains;
  gains.p_rp_per_s = -1.0;
  EXPECT_THROW(AttitudeController{gains}, std::invalid_argument);
  EXPECT_THROW(AttitudeController{}.Compute(kStart, Eigen::Vector3d::Zero(), 0.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
