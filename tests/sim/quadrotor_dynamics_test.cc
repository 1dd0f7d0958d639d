#include "sim/vehicle/quadrotor_dynamics.h"

#include <cmath>
#include <iostream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace aperture::sim {
namespace {

constexpr double kStep_s = 0.001;

// Rotor thrust commands that hold the vehicle in hover: each true thrust m g / 4, i.e. a commanded
// (load-cell) thrust m g / 4 / gamma_i.
control::RotorThrustCommand HoverCommand(const control::VehicleParameters& vehicle) {
  control::RotorThrustCommand command;
  const double f_N = vehicle.mass_kg * vehicle.gravity_mps2 / 4.0;
  command.thrust_N = Eigen::Vector4d::Constant(f_N).cwiseQuotient(vehicle.rotor_fitness);
  return command;
}

QuadrotorDynamics MakeSettledVehicle(const QuadrotorDynamicsParams& params,
                                     const control::QuadState& initial,
                                     const control::RotorThrustCommand& command) {
  QuadrotorDynamics vehicle(params, initial);
  vehicle.SetRotorThrustCommand(command);
  vehicle.SettleRotors();
  return vehicle;
}

class HoverTest : public ::testing::TestWithParam<Eigen::Vector4d> {};

TEST_P(HoverTest, HoverThrustHoldsPositionForTenSeconds) {
  QuadrotorDynamicsParams params;
  params.vehicle.rotor_fitness = GetParam();
  control::QuadState initial;
  initial.p_WB = Eigen::Vector3d(1.0, -2.0, 3.0);
  QuadrotorDynamics vehicle = MakeSettledVehicle(params, initial, HoverCommand(params.vehicle));
  double max_drift_m = 0.0;
  for (int k = 0; k < 10000; ++k) {
    vehicle.Step(kStep_s);
    max_drift_m = std::max(max_drift_m, (vehicle.state().p_WB - initial.p_WB).norm());
  }
  std::cout << "hover drift over 10 s with gamma = " << GetParam().transpose() << ": "
            << max_drift_m << " m\n";
  // Requirement of the simulator: an exact equilibrium may drift by at most 1 mm in 10 s.
  EXPECT_LT(max_drift_m, 1e-3);
  EXPECT_NEAR(vehicle.state().t_s, 10.0, 1e-9);
  // Equal true thrusts give no roll/pitch torque; with unequal gamma only the yaw drag torques
  // differ, which cannot tilt the vehicle.
  EXPECT_NEAR(vehicle.state().omega_B.head<2>().norm(), 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Fitness, HoverTest,
                         ::testing::Values(Eigen::Vector4d(1.0, 1.0, 1.0, 1.0),
                                           Eigen::Vector4d(0.9, 1.05, 1.0, 0.95)));

TEST(QuadrotorDynamicsTest, FreeFallWithMotorsOffMatchesHalfGTSquared) {
  QuadrotorDynamicsParams params;
  params.vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(0.8, 1.6, 0.8);  // f(-1) = 0: motors off
  params.vehicle.rotor_drag_D_per_s.setZero();
  QuadrotorDynamics vehicle(params);  // starts at the minimum command, settled
  ASSERT_EQ(vehicle.RotorThrusts_N().norm(), 0.0);
  vehicle.Step(2.0);
  // RK4 integrates the quadratic z(t) exactly; only rounding remains.
  const double g = params.vehicle.gravity_mps2;
  EXPECT_NEAR(vehicle.state().p_WB.z(), -0.5 * g * 4.0, 1e-9);
  EXPECT_NEAR(vehicle.state().v_W.z(), -g * 2.0, 1e-9);
  EXPECT_NEAR(vehicle.state().p_WB.head<2>().norm(), 0.0, 1e-12);
}

TEST(QuadrotorDynamicsTest, RotorDragDecaysHorizontalVelocityAsF2Predicts) {
  QuadrotorDynamicsParams params;  // D = diag(0.5, 0.35, 0)
  control::QuadState initial;
  const Eigen::Vector3d v0_W(2.0, -1.5, 0.0);
  initial.v_W = v0_W;
  QuadrotorDynamics vehicle = MakeSettledVehicle(params, initial, HoverCommand(params.vehicle));
  const Eigen::Vector3d d = params.vehicle.rotor_drag_D_per_s;
  double max_velocity_error = 0.0;
  for (int k = 1; k <= 3000; ++k) {
    vehicle.Step(kStep_s);
    const double t = k * kStep_s;
    const Eigen::Vector2d expected(v0_W.x() * std::exp(-d.x() * t), v0_W.y() * std::exp(-d.y() * t));
    max_velocity_error = std::max(max_velocity_error, (vehicle.state().v_W.head<2>() - expected).norm());
  }
  std::cout << "drag decay: max |v - v0 exp(-d t)| over 3 s = " << max_velocity_error << " m/s\n";
  // RK4 local error ~ (d h)^5 / 120 ~ 1e-18 per step: anything above 1e-9 is a model error.
  EXPECT_LT(max_velocity_error, 1e-9);
  const double t = 3.0;
  EXPECT_NEAR(vehicle.state().p_WB.x(), v0_W.x() / d.x() * (1.0 - std::exp(-d.x() * t)), 1e-9);
  EXPECT_NEAR(vehicle.state().p_WB.y(), v0_W.y() / d.y() * (1.0 - std::exp(-d.y() * t)), 1e-9);
  EXPECT_NEAR(vehicle.state().p_WB.z(), 0.0, 1e-9);  // d_z = 0, k_h = 0: hover thrust holds height
}

TEST(QuadrotorDynamicsTest, RotorDragActsAlongBodyAxesAtARotatedAttitude) {
  // (F.2) with the motors off (c = 0) and omega = 0: R is constant, and v_B = R^T v obeys
  // v_B' = -D v_B - g R^T z_W, one scalar ODE per body axis with the exact solution
  // v_Bi(t) = (v_Bi(0) + g_Bi / d_i) exp(-d_i t) - g_Bi / d_i. With d_x != d_y != d_z and a yawed
  // and tilted attitude, a drag applied in W (D v_W) or with R instead of R^T misses it by O(1).
  QuadrotorDynamicsParams params;
  params.vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(0.8, 1.6, 0.8);  // f(-1) = 0: motors off
  params.vehicle.rotor_drag_D_per_s = Eigen::Vector3d(0.6, 0.25, 0.1);
  control::QuadState initial;
  initial.q_WB = Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()) *  // yaw ~30 deg
                 Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *   // pitch
                 Eigen::AngleAxisd(-0.15, Eigen::Vector3d::UnitX());  // roll
  initial.v_W = Eigen::Vector3d(3.0, -2.0, 0.5);
  QuadrotorDynamics vehicle(params, initial);
  ASSERT_EQ(vehicle.RotorThrusts_N().norm(), 0.0);
  const Eigen::Matrix3d R_WB = initial.q_WB.toRotationMatrix();
  const Eigen::Array3d d = params.vehicle.rotor_drag_D_per_s.array();
  const Eigen::Array3d g_B =
      (R_WB.transpose() * Eigen::Vector3d(0, 0, params.vehicle.gravity_mps2)).array();
  const Eigen::Array3d v0_B = (R_WB.transpose() * initial.v_W).array();
  // Instantaneous acceleration against (F.2) itself.
  EXPECT_TRUE(
      (R_WB.transpose() * vehicle.Acceleration_W()).isApprox((-d * v0_B - g_B).matrix(), 1e-12));
  Eigen::Array3d max_error_B = Eigen::Array3d::Zero();
  for (int k = 1; k <= 2000; ++k) {
    vehicle.Step(kStep_s);
    const double t = k * kStep_s;
    const Eigen::Array3d expected_B = (v0_B + g_B / d) * (-d * t).exp() - g_B / d;
    const Eigen::Array3d v_B = (R_WB.transpose() * vehicle.state().v_W).array();
    max_error_B = max_error_B.max((v_B - expected_B).abs());
  }
  std::cout << "rotated drag decay: max |v_B - analytic| per body axis over 2 s = "
            << max_error_B.transpose() << " m/s\n";
  // RK4 local error ~ (d h)^5 / 120: anything above 1e-9 is a model error.
  EXPECT_LT(max_error_B.maxCoeff(), 1e-9);
  EXPECT_TRUE(vehicle.state().q_WB.isApprox(initial.q_WB, 1e-12));  // no torque: R stayed fixed
}

TEST(QuadrotorDynamicsTest, HorizontalSpeedAddsKhTermToCollectiveThrust) {
  QuadrotorDynamicsParams params;
  params.vehicle.thrust_velocity_coeff_kh = 0.05;
  control::QuadState initial;
  initial.v_W = Eigen::Vector3d(3.0, 1.0, 0.0);
  const QuadrotorDynamics vehicle = MakeSettledVehicle(params, initial, HoverCommand(params.vehicle));
  const double v_h = 3.0 + 1.0;  // v^T (x_B + y_B) at level attitude (F.5)
  const double g = params.vehicle.gravity_mps2;
  EXPECT_NEAR(vehicle.CollectiveThrust_mps2(), g + 0.05 * v_h * v_h, 1e-12);
  EXPECT_NEAR(vehicle.Acceleration_W().z(), 0.05 * v_h * v_h, 1e-12);
}

TEST(QuadrotorDynamicsTest, TiltedThrustAcceleratesAlongBodyZ) {
  QuadrotorDynamicsParams params;
  params.vehicle.rotor_drag_D_per_s.setZero();
  control::QuadState initial;
  const double roll = 0.3;
  initial.q_WB = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  const QuadrotorDynamics vehicle = MakeSettledVehicle(params, initial, HoverCommand(params.vehicle));
  const double g = params.vehicle.gravity_mps2;
  // z_B = (0, -sin(roll), cos(roll)) carries c = g.
  EXPECT_TRUE(vehicle.Acceleration_W().isApprox(
      Eigen::Vector3d(0.0, -g * std::sin(roll), g * std::cos(roll) - g), 1e-12));
}

// Measures the time at which a rotor's thrust crosses 63.2 % of a step, by linear interpolation
// between 0.1 ms samples.
double MeasureTimeConstant(QuadrotorDynamics* vehicle, double u_target) {
  const double f_start = vehicle->RotorThrusts_N()[0];
  vehicle->SetMotorCommands(Eigen::Vector4d::Constant(u_target));
  const double f_end = vehicle->params().vehicle.rotor.ThrustFromCommand(u_target);
  const double level = f_start + (1.0 - std::exp(-1.0)) * (f_end - f_start);
  const double h = 1e-4;
  double previous = f_start;
  for (int k = 1; k < 2000; ++k) {
    vehicle->Step(h);
    const double f = vehicle->RotorThrusts_N()[0];
    if ((f - level) * (previous - level) <= 0.0) {
      return h * (k - 1) + h * (level - previous) / (f - previous);
    }
    previous = f;
  }
  return -1.0;
}

TEST(QuadrotorDynamicsTest, MotorStepResponsesMatchUpAndDownTimeConstants) {
  QuadrotorDynamicsParams params;
  QuadrotorDynamics vehicle(params);
  const double tau_up = MeasureTimeConstant(&vehicle, 0.8);
  vehicle.Step(0.5);  // settle at the high command
  const double tau_down = MeasureTimeConstant(&vehicle, -0.9);
  std::cout << "step response 63.2 % times: up " << tau_up * 1e3 << " ms, down " << tau_down * 1e3
            << " ms\n";
  // The lag is solved in closed form; linear interpolation of the exponential over 0.1 ms errs
  // by < h^2 / (8 tau) ~ 1e-7 s.
  EXPECT_NEAR(tau_up, params.vehicle.rotor.time_constant_up_s, 1e-6);
  EXPECT_NEAR(tau_down, params.vehicle.rotor.time_constant_down_s, 1e-6);
}

TEST(QuadrotorDynamicsTest, DisabledRotorLagAppliesThrustImmediately) {
  QuadrotorDynamicsParams params;
  params.rotor_lag_enabled = false;
  QuadrotorDynamics vehicle(params);
  const Eigen::Vector4d u(0.5, -0.2, 0.1, 0.9);
  vehicle.SetMotorCommands(u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(vehicle.RotorThrusts_N()[i], params.vehicle.rotor.ThrustFromCommand(u[i]));
  }
  vehicle.Step(0.001);
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(vehicle.RotorThrusts_N()[i], params.vehicle.rotor.ThrustFromCommand(u[i]));
  }
}

TEST(QuadrotorDynamicsTest, ThrustCommandsAreScaledByFitnessAndClamped) {
  QuadrotorDynamicsParams params;
  params.vehicle.rotor_fitness = Eigen::Vector4d(0.8, 1.0, 1.1, 0.9);
  QuadrotorDynamics vehicle(params);
  control::RotorThrustCommand command;
  command.thrust_N = Eigen::Vector4d(1.0, 2.0, 100.0, -1.0);
  vehicle.SetRotorThrustCommand(command);
  vehicle.SettleRotors();
  const control::RotorParameters& rotor = params.vehicle.rotor;
  const Eigen::Vector4d expected(0.8 * 1.0, 2.0, 1.1 * rotor.MaxThrust(), 0.9 * rotor.MinThrust());
  EXPECT_TRUE(vehicle.RotorThrusts_N().isApprox(expected, 1e-12)) << vehicle.RotorThrusts_N().transpose();
  // The inverse of (G.3) at the idle thrust loses digits where the thrust map is flat (slope 0.1).
  EXPECT_NEAR(vehicle.motor_commands()[2], rotor.command_max, 1e-9);
  EXPECT_NEAR(vehicle.motor_commands()[3], rotor.command_min, 1e-9);
}

struct TorqueCase {
  const char* name;
  Eigen::Vector4d thrust_signs;  // rotor i gets f0 + sign_i * delta
  int axis;
};

class BodyTorqueTest : public ::testing::TestWithParam<TorqueCase> {};

TEST_P(BodyTorqueTest, SpinsUpTheAxisAsInertiaPredicts) {
  QuadrotorDynamicsParams params;
  const control::VehicleParameters& p = params.vehicle;
  const double f0 = p.mass_kg * p.gravity_mps2 / 4.0, delta = 0.05;
  control::RotorThrustCommand command;
  command.thrust_N = Eigen::Vector4d::Constant(f0) + delta * GetParam().thrust_signs;
  QuadrotorDynamics vehicle = MakeSettledVehicle(params, control::QuadState(), command);
  // Expected torque written from (G.1) and (G.5) directly, independent of the implementation.
  const Eigen::Vector4d f = command.thrust_N;
  const double arm = std::sqrt(2.0) / 2.0 * p.arm_length_m;
  Eigen::Vector4d kappa_f;
  for (int i = 0; i < 4; ++i) kappa_f[i] = p.rotor.TorqueCoefficient(f[i]) * f[i];
  const Eigen::Vector3d eta(arm * (f[0] - f[1] - f[2] + f[3]), arm * (-f[0] - f[1] + f[2] + f[3]),
                            kappa_f[0] - kappa_f[1] + kappa_f[2] - kappa_f[3]);
  const int axis = GetParam().axis;
  ASSERT_GT(std::abs(eta[axis]), 1e-4);
  EXPECT_NEAR((eta - eta[axis] * Eigen::Vector3d::Unit(axis)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(vehicle.RotorTorque_B().isApprox(eta, 1e-12));
  const double duration_s = 0.2;
  vehicle.Step(duration_s);
  // Single-axis rotation with a diagonal J has omega x J omega = 0: omega = eta t / J_axis.
  const double expected = eta[axis] * duration_s / p.inertia_diag_kgm2[axis];
  EXPECT_NEAR(vehicle.state().omega_B[axis], expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(vehicle.state().omega_B.norm(), std::abs(expected), 1e-9 * std::abs(expected));
}

INSTANTIATE_TEST_SUITE_P(
    G1, BodyTorqueTest,
    ::testing::Values(TorqueCase{"roll", Eigen::Vector4d(1, -1, -1, 1), 0},
                      TorqueCase{"pitch", Eigen::Vector4d(-1, -1, 1, 1), 1},
                      TorqueCase{"yaw", Eigen::Vector4d(1, -1, 1, -1), 2}),
    [](const ::testing::TestParamInfo<TorqueCase>& info) { return std::string(info.param.name); });

TEST(QuadrotorDynamicsTest, TorqueFreeTumblingKeepsMomentumAndEnergy) {
  QuadrotorDynamicsParams params;
  params.vehicle.inertia_diag_kgm2 = Eigen::Vector3d(1.0e-3, 1.5e-3, 2.5e-3);
  control::QuadState initial;
  initial.omega_B = Eigen::Vector3d(0.2, 6.0, 0.3);  // near the unstable intermediate axis: flips
  // Equal rotor thrusts: zero arm torque and cancelling drag torques (G.1); B = 0.
  QuadrotorDynamics vehicle(params, initial);
  const Eigen::Matrix3d J = params.vehicle.Inertia();
  const Eigen::Vector3d momentum0_W = initial.q_WB * (J * initial.omega_B);
  const double energy0 = 0.5 * initial.omega_B.dot(J * initial.omega_B);
  vehicle.Step(20.0);
  const control::QuadState& s = vehicle.state();
  const Eigen::Vector3d momentum_W = s.q_WB * (J * s.omega_B);
  const double energy = 0.5 * s.omega_B.dot(J * s.omega_B);
  // RK4 at 1 ms and |omega| = 6 rad/s: local error ~ (6e-3)^5 per step, 2e4 steps -> ~1e-7
  // relative; a sign error in omega x J omega or in q' would break these by O(1).
  EXPECT_LT((momentum_W - momentum0_W).norm() / momentum0_W.norm(), 1e-6);
  EXPECT_NEAR(energy / energy0, 1.0, 1e-6);
  EXPECT_GT(std::abs(s.omega_B.y() - initial.omega_B.y()), 1.0) << "expected a tumbling motion";
}

TEST(QuadrotorDynamicsTest, FastSpinKeepsTheQuaternionUnitAndTheAnalyticAttitude) {
  // 50 rad/s about the principal axis z_B: omega x J omega = 0, so R(t) = Rz(50 t) exactly. RK4
  // shrinks |q| by ~(omega h / 2)^6 / 144 ~ 2e-12 per 1 ms step here (a pure rotation's stability
  // polynomial), ~4e-9 after 2 s: only the renormalization after every step keeps it below 1e-12.
  QuadrotorDynamicsParams params;
  control::QuadState initial;
  const double rate = 50.0;
  initial.omega_B = Eigen::Vector3d(0.0, 0.0, rate);
  QuadrotorDynamics vehicle(params, initial);  // equal rotor commands: the yaw torques cancel
  double max_norm_error = 0.0;
  for (int k = 1; k <= 2000; ++k) {
    vehicle.Step(kStep_s);
    max_norm_error = std::max(max_norm_error, std::abs(vehicle.state().q_WB.norm() - 1.0));
  }
  EXPECT_LT(max_norm_error, 1e-12);
  // Phase error of RK4 ~ (omega h)^5 / 120 per step ~ 3e-9 rad; 2000 steps ~ 1e-5 rad at most.
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(rate * 2.0, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(vehicle.state().q_WB.angularDistance(expected), 1e-5);
  EXPECT_NEAR(vehicle.state().omega_B.z(), rate, 1e-9);
}

TEST(QuadrotorDynamicsTest, RotorDragTorqueBDampsBodyRate) {
  QuadrotorDynamicsParams params;
  const double b = 2e-3;  // [N m s/rad]
  params.vehicle.rotor_drag_B = b * Eigen::Matrix3d::Identity();
  control::QuadState initial;
  initial.omega_B = Eigen::Vector3d(3.0, 0.0, 0.0);
  QuadrotorDynamics vehicle(params, initial);
  vehicle.Step(0.5);
  // (F.4): J_xx omega' = -b omega  ->  omega(t) = omega0 exp(-b t / J_xx).
  const double expected = 3.0 * std::exp(-b * 0.5 / params.vehicle.inertia_diag_kgm2.x());
  EXPECT_NEAR(vehicle.state().omega_B.x(), expected, 1e-9);
}

TEST(QuadrotorDynamicsTest, RejectsBadInputsNamingThem) {
  QuadrotorDynamicsParams params;
  params.max_integration_step_s = 0.0;
  EXPECT_THROW(QuadrotorDynamics{params}, std::invalid_argument);
  params = QuadrotorDynamicsParams();
  params.vehicle.mass_kg = -1.0;
  try {
    QuadrotorDynamics vehicle(params);
    FAIL() << "negative mass accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mass_kg"), std::string::npos) << e.what();
  }
  params = QuadrotorDynamicsParams();
  params.vehicle.rotor.time_constant_up_s = 1e-4;  // faster than the 1 ms step can resolve
  EXPECT_THROW(QuadrotorDynamics{params}, std::invalid_argument);
  params.rotor_lag_enabled = false;
  EXPECT_NO_THROW(QuadrotorDynamics{params});
  QuadrotorDynamics vehicle{QuadrotorDynamicsParams()};
  EXPECT_THROW(vehicle.Step(0.0), std::invalid_argument);
  EXPECT_THROW(vehicle.SetMotorCommands(Eigen::Vector4d::Constant(NAN)), std::invalid_argument);
  control::QuadState bad;
  bad.q_WB.coeffs() << 0.0, 0.0, 0.0, 2.0;
  EXPECT_THROW(vehicle.SetState(bad), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim

namespace aperture::sim {
namespace {

QuadrotorDynamicsParams GroundParams() {
  QuadrotorDynamicsParams params;
  params.ground_contact_enabled = true;
  params.ground_height_m = 0.2;
  return params;
}

TEST(GroundContactTest, IdleVehicleRestsOnTheGroundAndFeelsItsReaction) {
  control::QuadState initial;
  initial.p_WB = Eigen::Vector3d(1.0, 2.0, 0.2);
  QuadrotorDynamics vehicle(GroundParams(), initial);  // idle thrust 4 x 0.05 N < weight 4.4 N
  vehicle.Step(1.0);
  EXPECT_TRUE(vehicle.on_ground());
  EXPECT_TRUE(vehicle.state().p_WB.isApprox(initial.p_WB, 1e-12));
  EXPECT_EQ(vehicle.state().v_W, Eigen::Vector3d::Zero());
  EXPECT_TRUE(vehicle.SpecificForce_B().isApprox(Eigen::Vector3d(0, 0, 9.81), 1e-12));
  EXPECT_NEAR(vehicle.Acceleration_W().norm(), 0.0, 1e-12);
}

TEST(GroundContactTest, TakesOffWhenThrustExceedsWeight) {
  const QuadrotorDynamicsParams params = GroundParams();
  control::QuadState initial;
  initial.p_WB.z() = params.ground_height_m;
  QuadrotorDynamics vehicle(params, initial);
  control::RotorThrustCommand command;
  command.thrust_N.setConstant(1.5);  // c = 6 / 0.45 = 13.33 m/s^2
  vehicle.SetRotorThrustCommand(command);
  vehicle.SettleRotors();
  vehicle.Step(1.0);
  EXPECT_FALSE(vehicle.on_ground());
  // D has no z component: a straight climb at c - g from rest.
  const double climb = 0.5 * (6.0 / 0.45 - 9.81);
  EXPECT_NEAR(vehicle.state().p_WB.z(), params.ground_height_m + climb, 1e-9);
}

TEST(GroundContactTest, DropLandsAtFreeFallSpeedAndComesToRestUpright) {
  QuadrotorDynamicsParams params = GroundParams();
  params.vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(0.8, 1.6, 0.8);  // motors off: f(-1) = 0
  params.vehicle.rotor_drag_D_per_s.setZero();
  const double drop_m = 1.0;
  control::QuadState initial;
  initial.p_WB.z() = params.ground_height_m + drop_m;
  const double yaw = 0.7;
  initial.q_WB = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                 Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
  QuadrotorDynamics vehicle(params, initial);
  EXPECT_FALSE(vehicle.on_ground());
  vehicle.Step(1.0);  // lands after sqrt(2 h / g) = 0.45 s
  EXPECT_TRUE(vehicle.on_ground());
  // Touchdown is detected at the end of the 1 ms step that crosses the plane: the speed is then
  // up to g * 1 ms above sqrt(2 g h).
  const double g = params.vehicle.gravity_mps2;
  EXPECT_GE(vehicle.last_touchdown_speed_mps(), std::sqrt(2.0 * g * drop_m));
  EXPECT_LE(vehicle.last_touchdown_speed_mps(), std::sqrt(2.0 * g * drop_m) + g * 1e-3);
  EXPECT_NEAR(vehicle.state().p_WB.z(), params.ground_height_m, 0.0);
  const Eigen::Vector3d z_B_W = vehicle.state().q_WB * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(z_B_W.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  const Eigen::Vector3d x_B_W = vehicle.state().q_WB * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(std::atan2(x_B_W.y(), x_B_W.x()), yaw, 1e-12);
}

}  // namespace
}  // namespace aperture::sim
