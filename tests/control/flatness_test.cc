#include "control/flatness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/reference_trajectories.h"
#include "control/so3.h"
#include "tests/support/scientific.h"

namespace aperture::control {
namespace {

using test_support::Sci;

// Measured figure for the XML test report, in scientific notation.

// A smooth 3D test trajectory with analytic derivatives: every axis a sum of a sinusoid and a
// slow drift, heading psi(t) = 0.2 t + 0.4 sin(0.9 t). Accelerations stay below 5 m/s^2 so the
// thrust never vanishes and the heading never meets the singularity.
TrajectoryPoint WobbleTrajectory(double t) {
  const Eigen::Vector3d amp(1.2, 0.8, 0.5), w(1.7, 2.3, 1.3), phase(0.1, 0.7, -0.4);
  TrajectoryPoint point;
  point.t_s = t;
  for (int i = 0; i < 3; ++i) {
    const double s = std::sin(w[i] * t + phase[i]), c = std::cos(w[i] * t + phase[i]);
    const double a = amp[i], wi = w[i];
    point.p_W[i] = a * s + 0.3 * t;
    point.v_W[i] = a * wi * c + 0.3;
    point.a_W[i] = -a * wi * wi * s;
    point.j_W[i] = -a * wi * wi * wi * c;
    point.s_W[i] = a * wi * wi * wi * wi * s;
  }
  point.heading_rad = 0.2 * t + 0.4 * std::sin(0.9 * t);
  point.heading_rate_radps = 0.2 + 0.36 * std::cos(0.9 * t);
  point.heading_acc_radps2 = -0.324 * std::sin(0.9 * t);
  return point;
}

// All drag terms non-zero and asymmetric (dz != 0 exercises every term of F.17-F.30).
VehicleParameters FullDragVehicle() {
  VehicleParameters vehicle;
  vehicle.rotor_drag_D_per_s = Eigen::Vector3d(0.544, 0.386, 0.1);
  vehicle.thrust_velocity_coeff_kh = 0.009;  // F.7.3
  vehicle.rotor_drag_A << 1e-3, 2e-4, 0.0, -3e-4, 8e-4, 1e-4, 0.0, 5e-4, 2e-4;
  vehicle.rotor_drag_B = Eigen::Vector3d(2e-4, 3e-4, 1e-4).asDiagonal();
  return vehicle;
}

VehicleParameters DragFreeVehicle() {
  VehicleParameters vehicle;
  vehicle.rotor_drag_D_per_s.setZero();
  vehicle.thrust_velocity_coeff_kh = 0.0;
  return vehicle;
}

// Body rates from central differences of R(t): omega^ = R' dR/dt (F.3).
Eigen::Vector3d NumericOmega(double t, const VehicleParameters& vehicle, double h) {
  const Eigen::Matrix3d R = ComputeFlatnessOutputs(WobbleTrajectory(t), vehicle).R_WB;
  const Eigen::Matrix3d R_plus = ComputeFlatnessOutputs(WobbleTrajectory(t + h), vehicle).R_WB;
  const Eigen::Matrix3d R_minus = ComputeFlatnessOutputs(WobbleTrajectory(t - h), vehicle).R_WB;
  return Vee(R.transpose() * (R_plus - R_minus) / (2.0 * h));
}

bool AllFinite(const FlatnessResult& r) {
  return r.R_WB.allFinite() && r.q_WB.coeffs().allFinite() &&
         std::isfinite(r.collective_thrust_mps2) && std::isfinite(r.thrust_command_mps2) &&
         std::isfinite(r.collective_thrust_rate_mps3) && r.omega_B.allFinite() &&
         r.omega_dot_B.allFinite() && r.tau_B_Nm.allFinite();
}

TEST(FlatnessTest, DragFreeCaseEqualsClassicThrustDirectionAndRates) {
  const VehicleParameters vehicle = DragFreeVehicle();
  const Eigen::Vector3d g_W(0.0, 0.0, vehicle.gravity_mps2);
  for (double t = 0.0; t < 10.0; t += 0.37) {
    const TrajectoryPoint ref = WobbleTrajectory(t);
    const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
    ASSERT_TRUE(r.ok()) << r;
    // Classic (Mellinger & Kumar) thrust direction and magnitude, heading axis of B.18.
    const Eigen::Vector3d thrust = ref.a_W + g_W;
    const Eigen::Vector3d z_B = thrust.normalized();
    const Eigen::Vector3d y_C(-std::sin(ref.heading_rad), std::cos(ref.heading_rad), 0.0);
    const Eigen::Vector3d x_B = y_C.cross(z_B).normalized();
    const Eigen::Vector3d y_B = z_B.cross(x_B);
    const double c = thrust.norm();
    // Classic rates: h = (j - (z_B'j) z_B) / c, omega_x = -h'y_B, omega_y = h'x_B.
    const Eigen::Vector3d h = (ref.j_W - z_B.dot(ref.j_W) * z_B) / c;
    // Round-off only: unit vectors from a handful of flops on O(10) inputs.
    EXPECT_LT((r.R_WB.col(0) - x_B).norm(), 1e-12);
    EXPECT_LT((r.R_WB.col(1) - y_B).norm(), 1e-12);
    EXPECT_LT((r.R_WB.col(2) - z_B).norm(), 1e-12);
    EXPECT_NEAR(r.collective_thrust_mps2, c, 1e-12);
    EXPECT_NEAR(r.thrust_command_mps2, c, 1e-12);
    EXPECT_NEAR(r.omega_B.x(), -h.dot(y_B), 1e-12);
    EXPECT_NEAR(r.omega_B.y(), h.dot(x_B), 1e-12);
    EXPECT_NEAR(r.collective_thrust_rate_mps3, z_B.dot(ref.j_W), 1e-12);
  }
}

TEST(FlatnessTest, OrientationIsRotationAndSatisfiesDragModelF2AndThrustModelF5) {
  const VehicleParameters vehicle = FullDragVehicle();
  const Eigen::Matrix3d D = vehicle.rotor_drag_D_per_s.asDiagonal();
  double max_residual = 0.0;
  for (double t = 0.0; t < 10.0; t += 0.13) {
    const TrajectoryPoint ref = WobbleTrajectory(t);
    const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
    ASSERT_TRUE(r.ok()) << r;
    const Eigen::Matrix3d& R = r.R_WB;
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LT((r.q_WB.toRotationMatrix() - R).norm(), 1e-12);
    // (F.2): v' = -g z_W + c z_B - R D R' v.
    const Eigen::Vector3d model = -vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ() +
                                  r.collective_thrust_mps2 * R.col(2) -
                                  R * D * R.transpose() * ref.v_W;
    max_residual = std::max(max_residual, (model - ref.a_W).norm());
    // (F.5): c = c_cmd + k_h (v'(x_B + y_B))^2.
    const double v_h = ref.v_W.dot(R.col(0) + R.col(1));
    EXPECT_NEAR(r.thrust_command_mps2 + vehicle.thrust_velocity_coeff_kh * v_h * v_h,
                r.collective_thrust_mps2, 1e-12);
    // Heading (F.9)-(F.11): x_B projects onto x_C, i.e. x_B is orthogonal to y_C.
    const Eigen::Vector3d x_C(std::cos(ref.heading_rad), std::sin(ref.heading_rad), 0.0);
    const Eigen::Vector3d y_C(-x_C.y(), x_C.x(), 0.0);
    EXPECT_NEAR(R.col(0).dot(y_C), 0.0, 1e-12);
    EXPECT_GT(R.col(0).dot(x_C), 0.0);
  }
  RecordProperty("max_F2_residual_mps2", Sci(max_residual));
  EXPECT_LT(max_residual, 1e-9);  // the project's bound; exact algebra, round-off ~1e-14
}

TEST(FlatnessTest, BodyRatesMatchNumericDerivativeOfOrientation) {
  for (const VehicleParameters& vehicle : {DragFreeVehicle(), FullDragVehicle()}) {
    double max_error = 0.0;
    for (double t = 0.05; t < 10.0; t += 0.11) {
      const FlatnessResult r = ComputeFlatnessOutputs(WobbleTrajectory(t), vehicle);
      ASSERT_TRUE(r.ok()) << r;
      max_error = std::max(max_error, (r.omega_B - NumericOmega(t, vehicle, 1e-5)).norm());
    }
    // Central differences with h = 1e-5: truncation ~h^2 |R'''| ~ 1e-9, round-off ~1e-16/h.
    RecordProperty("max_omega_error_radps", Sci(max_error));
    EXPECT_LT(max_error, 1e-7);
  }
}

TEST(FlatnessTest, AngularAccelerationAndThrustRateMatchNumericDerivatives) {
  for (const VehicleParameters& vehicle : {DragFreeVehicle(), FullDragVehicle()}) {
    double max_error = 0.0, max_c_dot_error = 0.0;
    const double h = 1e-5;
    for (double t = 0.05; t < 10.0; t += 0.11) {
      const FlatnessResult r = ComputeFlatnessOutputs(WobbleTrajectory(t), vehicle);
      const FlatnessResult plus = ComputeFlatnessOutputs(WobbleTrajectory(t + h), vehicle);
      const FlatnessResult minus = ComputeFlatnessOutputs(WobbleTrajectory(t - h), vehicle);
      const Eigen::Vector3d numeric = (plus.omega_B - minus.omega_B) / (2.0 * h);
      max_error = std::max(max_error, (r.omega_dot_B - numeric).norm());
      const double c_dot = (plus.collective_thrust_mps2 - minus.collective_thrust_mps2) / (2 * h);
      max_c_dot_error = std::max(max_c_dot_error, std::abs(r.collective_thrust_rate_mps3 - c_dot));
    }
    // Same central-difference budget as the body rates.
    RecordProperty("max_omega_dot_error_radps2", Sci(max_error));
    EXPECT_LT(max_error, 1e-6);
    EXPECT_LT(max_c_dot_error, 1e-6);
  }
}

TEST(FlatnessTest, TorqueSatisfiesRigidBodyDynamicsF4) {
  const VehicleParameters vehicle = FullDragVehicle();
  const Eigen::Matrix3d J = vehicle.Inertia();
  const double h = 1e-5;
  for (double t = 0.05; t < 10.0; t += 0.29) {
    const TrajectoryPoint ref = WobbleTrajectory(t);
    const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
    const Eigen::Vector3d omega_dot =
        (ComputeFlatnessOutputs(WobbleTrajectory(t + h), vehicle).omega_B -
         ComputeFlatnessOutputs(WobbleTrajectory(t - h), vehicle).omega_B) /
        (2.0 * h);
    // (F.4) with tau_g = 0, J omega' = tau - omega x J omega - A R'v - B omega.
    const Eigen::Vector3d lhs = J * omega_dot;
    const Eigen::Vector3d rhs = r.tau_B_Nm - r.omega_B.cross(J * r.omega_B) -
                                vehicle.rotor_drag_A * r.R_WB.transpose() * ref.v_W -
                                vehicle.rotor_drag_B * r.omega_B;
    // J ~ 1e-3 times the 1e-6 rad/s^2 differentiation error.
    EXPECT_LT((lhs - rhs).norm(), 1e-8);
  }
}

TEST(FlatnessTest, CircleReproducesThesisThrustAndBodyRates) {
  // F.7.2: radius 1.8 m at 4 m/s without drag: c = 13.24 m/s^2 and |omega| = 85 deg/s. The 85
  // deg/s is the roll/pitch part Omega sin(tilt); with the heading of (F.11) held constant the
  // yaw rate of (F.25) oscillates on top of it (0 to ~77 deg/s), so the figure is checked on
  // [omega_x, omega_y].
  const CircleTrajectory circle;
  const VehicleParameters vehicle = DragFreeVehicle();
  for (double t = 4.0; t < 8.0; t += 0.25) {  // inside the full-speed part (ramp ends at 3 s)
    const FlatnessResult r = ComputeFlatnessOutputs(circle.Evaluate(t), vehicle);
    EXPECT_NEAR(r.collective_thrust_mps2, 13.24, 0.005);             // thesis rounds to 0.01
    EXPECT_NEAR(r.omega_B.head<2>().norm() * kRadToDeg, 85.0, 0.5);  // thesis rounds to 1 deg/s
  }
}

TEST(FlatnessTest, LemniscateReproducesThesisPeakThrustAndBodyRates) {
  // F.7.2: Gerono lemniscate at 4 m/s peak speed: max c = 12.98 m/s^2, max |omega| = 136 deg/s.
  const LemniscateTrajectory lemniscate;
  const VehicleParameters vehicle = DragFreeVehicle();
  double max_c = 0.0, max_omega = 0.0;
  for (double t = 4.0; t < 4.0 + 2.0 * M_PI / std::sqrt(2.0); t += 1e-3) {
    const FlatnessResult r = ComputeFlatnessOutputs(lemniscate.Evaluate(t), vehicle);
    max_c = std::max(max_c, r.collective_thrust_mps2);
    max_omega = std::max(max_omega, r.omega_B.norm() * kRadToDeg);
  }
  EXPECT_NEAR(max_c, 12.98, 0.005);
  EXPECT_NEAR(max_omega, 136.0, 0.5);
}

TEST(FlatnessTest, BodyFrameVelocitiesMatchThesisForHeadingZero) {
  // F.7.2: max nominal velocity 4.0 m/s in the x_B-y_B plane and 0 along z_B on the circle;
  // 2.8 m/s along x_B and y_B and 1.3 m/s along z_B on the lemniscate (thesis rounding 0.05).
  const VehicleParameters vehicle = DragFreeVehicle();
  auto max_body_velocity = [&](const ReferenceTrajectory& trajectory, double period_s) {
    Eigen::Vector3d max_v_B = Eigen::Vector3d::Zero();
    for (double t = 4.0; t < 4.0 + period_s; t += 1e-3) {
      const TrajectoryPoint ref = trajectory.Evaluate(t);
      const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
      max_v_B = max_v_B.cwiseMax((r.R_WB.transpose() * ref.v_W).cwiseAbs());
    }
    return max_v_B;
  };
  const Eigen::Vector3d lemniscate =
      max_body_velocity(LemniscateTrajectory(), 2.0 * M_PI / std::sqrt(2.0));
  EXPECT_NEAR(lemniscate.x(), 2.8, 0.05);
  EXPECT_NEAR(lemniscate.y(), 2.8, 0.05);
  EXPECT_NEAR(lemniscate.z(), 1.3, 0.05);
  const Eigen::Vector3d circle = max_body_velocity(CircleTrajectory(), 2.0 * M_PI * 1.8 / 4.0);
  EXPECT_NEAR(circle.head<2>().maxCoeff(), 4.0, 1e-6);
  EXPECT_LT(circle.z(), 1e-12);  // z_B is tilted towards the centre, v is tangential
}

TEST(FlatnessTest, YawSingularityGivesFiniteOutputsFlagAndUprightLimit) {
  const VehicleParameters vehicle = FullDragVehicle();
  TrajectoryPoint ref;
  ref.heading_rad = 0.0;  // y_C = y_W
  ref.heading_rate_radps = 0.5;
  ref.heading_acc_radps2 = 0.2;
  ref.j_W = Eigen::Vector3d(0.3, -0.2, 0.1);
  // v = 0 so alpha = a + g z_W = [0, 2g, 0] is parallel to y_C.
  ref.a_W = Eigen::Vector3d(0.0, 2.0 * vehicle.gravity_mps2, -vehicle.gravity_mps2);
  const FlatnessResult singular = ComputeFlatnessOutputs(ref, vehicle);
  EXPECT_EQ(singular.status, FlatnessStatus::kYawSingular);
  EXPECT_TRUE(AllFinite(singular)) << singular;
  EXPECT_EQ(singular.omega_B.z(), 0.0);
  EXPECT_EQ(singular.omega_dot_B.z(), 0.0);
  const Eigen::Vector3d alpha = ref.a_W + vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(singular.R_WB.col(0).dot(alpha), 0.0, 1e-12);  // (F.7) still holds
  EXPECT_GT(singular.R_WB.col(2).dot(alpha), 0.0);
  // Just outside the threshold with thrust tilted upwards, (F.11) lands next to the fallback.
  TrajectoryPoint near = ref;
  near.a_W.z() += 2.0 * kYawSingularity * alpha.norm();
  const FlatnessResult regular = ComputeFlatnessOutputs(near, vehicle);
  EXPECT_EQ(regular.status, FlatnessStatus::kOk);
  // Angle between the two orientations ~ 2 kYawSingularity.
  EXPECT_LT((regular.R_WB - singular.R_WB).norm(), 5.0 * kYawSingularity);
}

TEST(FlatnessTest, FreeFallReferenceGivesHeadingRotationAndFlag) {
  const VehicleParameters vehicle = FullDragVehicle();
  TrajectoryPoint ref;
  ref.a_W = Eigen::Vector3d(0.0, 0.0, -vehicle.gravity_mps2);
  ref.j_W = Eigen::Vector3d(1.0, 2.0, 0.0);
  ref.heading_rad = 0.7;
  ref.heading_rate_radps = 0.4;
  ref.heading_acc_radps2 = -0.3;
  const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
  EXPECT_EQ(r.status, FlatnessStatus::kNoThrust);
  EXPECT_TRUE(AllFinite(r)) << r;
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((r.R_WB - Rz).norm(), 1e-12);
  EXPECT_NEAR(r.collective_thrust_mps2, 0.0, 1e-12);
  EXPECT_LT((r.omega_B - Eigen::Vector3d(0.0, 0.0, 0.4)).norm(), 1e-12);
  EXPECT_LT((r.omega_dot_B - Eigen::Vector3d(0.0, 0.0, -0.3)).norm(), 1e-12);
}

TEST(FlatnessTest, VanishingRollPitchPivotGivesFiniteOutputsAndFlag) {
  // dx = 1, dy = 0: alpha = [0, 1, 0] and beta = [1, 0, 0] are orthogonal, so alpha lies along
  // y_B and the pivot z_B'alpha of (F.17) vanishes although both vectors are non-zero.
  VehicleParameters vehicle;
  vehicle.rotor_drag_D_per_s = Eigen::Vector3d(1.0, 0.0, 0.0);
  TrajectoryPoint ref;
  ref.v_W = Eigen::Vector3d(-1.0, 1.0, 0.0);
  ref.a_W = Eigen::Vector3d(1.0, 0.0, -vehicle.gravity_mps2);
  ref.j_W = Eigen::Vector3d(0.5, 0.5, 0.5);
  ref.heading_rad = M_PI / 2.0;
  const FlatnessResult r = ComputeFlatnessOutputs(ref, vehicle);
  EXPECT_EQ(r.status, FlatnessStatus::kLowThrust);
  EXPECT_TRUE(AllFinite(r)) << r;
  EXPECT_EQ(r.omega_B.x(), 0.0);
  EXPECT_EQ(r.omega_B.y(), 0.0);
}

TEST(FlatnessTest, NonFiniteReferenceThrowsNamingTheTime) {
  TrajectoryPoint ref;
  ref.t_s = 2.5;
  ref.j_W.y() = std::nan("");
  try {
    ComputeFlatnessOutputs(ref, VehicleParameters{});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t = 2.5"), std::string::npos) << e.what();
  }
}

TEST(FlatnessTest, ResultPrintsStatusAndThrust) {
  TrajectoryPoint ref;
  std::ostringstream os;
  os << ComputeFlatnessOutputs(ref, DragFreeVehicle());
  EXPECT_NE(os.str().find("status=ok"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("c=9.81"), std::string::npos) << os.str();
}

}  // namespace
}  // namespace aperture::control
