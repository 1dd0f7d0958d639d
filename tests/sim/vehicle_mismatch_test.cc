#include "sim/sitl/vehicle_mismatch.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "control/reference_trajectories.h"
#include "control/rotor_thrust_estimator.h"
#include "sim/sim_params_io.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/tracking_flight.h"
#include "sim/vehicle/quadrotor_dynamics.h"
#include "tests/support/message_of.h"
#include "tests/support/quiet_sitl_params.h"

namespace aperture::sim {
namespace {

using test_support::MessageOf;

TEST(VehicleMismatch, DrawsStayWithinTheBoundsAndDependOnlyOnTheSeed) {
  const VehicleMismatchBounds b;
  const auto within_factor = [](double factor, double relative) {
    return factor >= 1.0 - relative && factor <= 1.0 + relative;
  };
  double min_thrust_factor = 2.0, max_thrust_factor = 0.0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const VehicleMismatch m = DrawVehicleMismatch(b, seed);
    EXPECT_TRUE(within_factor(m.rotor_drag_factor_xy.x(), b.rotor_drag_relative));
    EXPECT_TRUE(within_factor(m.rotor_drag_factor_xy.y(), b.rotor_drag_relative));
    EXPECT_TRUE(within_factor(m.time_constant_up_factor, b.time_constant_relative));
    EXPECT_TRUE(within_factor(m.time_constant_down_factor, b.time_constant_relative));
    EXPECT_TRUE(within_factor(m.thrust_map_factor, b.thrust_map_relative));
    EXPECT_TRUE(within_factor(m.torque_map_factor, b.torque_map_relative));
    for (int i = 0; i < 4; ++i) {
      EXPECT_TRUE(within_factor(m.rotor_fitness_factor[i], b.rotor_fitness_relative));
    }
    EXPECT_GE(m.thrust_velocity_coeff_kh, 0.0);
    EXPECT_LE(m.thrust_velocity_coeff_kh, b.thrust_velocity_coeff_kh_max);
    EXPECT_LE(m.quadratic_drag_per_m, b.quadratic_drag_max_per_m);
    EXPECT_LE(m.drag_thrust_exponent, b.drag_thrust_exponent_max);
    EXPECT_LE(m.battery_sag_per_s, b.battery_sag_max_per_s);
    EXPECT_LE(m.esc_delay_s, b.esc_delay_max_s);
    EXPECT_LE(m.gyro_vibration_noise, b.gyro_vibration_noise_max);
    EXPECT_GE(m.command_latency_s, b.command_latency_s[0]);
    EXPECT_LE(m.command_latency_s, b.command_latency_s[1]);
    EXPECT_GE(m.estimate_latency_s, b.estimate_latency_s[0]);
    EXPECT_LE(m.estimate_latency_s, b.estimate_latency_s[1]);
    min_thrust_factor = std::min(min_thrust_factor, m.thrust_map_factor);
    max_thrust_factor = std::max(max_thrust_factor, m.thrust_map_factor);
  }
  // 200 draws spread over the range (not stuck at the nominal).
  EXPECT_LT(min_thrust_factor, 0.75);
  EXPECT_GT(max_thrust_factor, 1.25);
  const VehicleMismatch a = DrawVehicleMismatch(b, 7), again = DrawVehicleMismatch(b, 7);
  EXPECT_EQ(a.thrust_map_factor, again.thrust_map_factor);
  EXPECT_EQ(a.rotor_fitness_factor, again.rotor_fitness_factor);
  EXPECT_EQ(a.estimate_latency_s, again.estimate_latency_s);
  EXPECT_NE(a.thrust_map_factor, DrawVehicleMismatch(b, 8).thrust_map_factor);
}

TEST(VehicleMismatch, BadBoundsAreNamed) {
  VehicleMismatchBounds b;
  b.thrust_map_relative = 1.2;
  EXPECT_NE(MessageOf([&] { DrawVehicleMismatch(b, 1); }).find("thrust_map_relative"),
            std::string::npos);
  b = VehicleMismatchBounds();
  b.command_latency_s = Eigen::Vector2d(0.03, 0.02);
  EXPECT_NE(MessageOf([&] { b.Validate(); }).find("command_latency_s[1] (max)"), std::string::npos);
  QuadrotorDynamicsParams dynamics;
  dynamics.drag_thrust_exponent = 3.0;
  EXPECT_NE(MessageOf([&] { dynamics.Validate(); }).find("drag_thrust_exponent"),
            std::string::npos);
}

TEST(VehicleMismatch, ConfigSectionLoadsAndRejectsBadBounds) {
  config::ParamReader reader(YAML::Load(R"(
mismatch: true
mismatch_bounds: {thrust_map_relative: 0.1, command_latency_s: [0.02, 0.03]}
)"),
                             "test.yaml");
  VehicleMismatchParams params;
  LoadParams(reader, &params);
  EXPECT_TRUE(params.mismatch);
  EXPECT_EQ(params.mismatch_bounds.thrust_map_relative, 0.1);
  EXPECT_EQ(params.mismatch_bounds.command_latency_s, Eigen::Vector2d(0.02, 0.03));
  EXPECT_EQ(params.mismatch_bounds.torque_map_relative,
            VehicleMismatchBounds().torque_map_relative);
  config::ParamReader bad(YAML::Load("mismatch_bounds: {rotor_fitness_relative: -0.1}"),
                          "bad.yaml");
  EXPECT_NE(MessageOf([&] { LoadParams(bad, &params); }).find("rotor_fitness_relative"),
            std::string::npos);
}

TEST(VehicleMismatch, ApplyKeepsTheNominalModelForTheFlightController) {
  SitlRunnerParams sitl;
  const control::VehicleParameters nominal = sitl.dynamics.vehicle;
  const double gyro_density = sitl.imu.gyro_noise_density;
  const VehicleMismatch m = DrawVehicleMismatch(VehicleMismatchBounds(), 3);
  ApplyVehicleMismatch(m, &sitl);
  ASSERT_TRUE(sitl.flight_controller_model.has_value());
  EXPECT_EQ(sitl.flight_controller_model->rotor.thrust_coeffs_N, nominal.rotor.thrust_coeffs_N);
  const control::VehicleParameters& v = sitl.dynamics.vehicle;
  EXPECT_EQ(v.rotor.thrust_coeffs_N, m.thrust_map_factor * nominal.rotor.thrust_coeffs_N);
  EXPECT_EQ(v.rotor.torque_coeffs_Nm, m.torque_map_factor * nominal.rotor.torque_coeffs_Nm);
  EXPECT_EQ(v.rotor.time_constant_up_s,
            m.time_constant_up_factor * nominal.rotor.time_constant_up_s);
  EXPECT_EQ(v.rotor_fitness, m.rotor_fitness_factor);
  EXPECT_EQ(v.rotor_drag_D_per_s.x(), m.rotor_drag_factor_xy.x() * nominal.rotor_drag_D_per_s.x());
  EXPECT_EQ(v.rotor_drag_D_per_s.z(), nominal.rotor_drag_D_per_s.z());
  EXPECT_EQ(v.thrust_velocity_coeff_kh, m.thrust_velocity_coeff_kh);
  EXPECT_EQ(sitl.dynamics.quadratic_drag_per_m, m.quadratic_drag_per_m);
  EXPECT_EQ(sitl.dynamics.drag_thrust_exponent, m.drag_thrust_exponent);
  EXPECT_EQ(sitl.dynamics.battery_sag_per_s, m.battery_sag_per_s);
  EXPECT_EQ(sitl.command_latency_s, m.command_latency_s);
  EXPECT_EQ(sitl.estimate_latency_s, m.estimate_latency_s);
  EXPECT_EQ(sitl.esc_delay_s, m.esc_delay_s);
  EXPECT_DOUBLE_EQ(
      sitl.imu.gyro_noise_density,
      std::sqrt(gyro_density * gyro_density + m.gyro_vibration_noise * m.gyro_vibration_noise));
  // Off: nothing changes.
  SitlRunnerParams untouched;
  EXPECT_FALSE(ApplyVehicleMismatch(VehicleMismatchParams(), 3, &untouched).has_value());
  EXPECT_FALSE(untouched.flight_controller_model.has_value());
}

// ---------------------------------------------------------------------------------------------
// The dynamics' extra drag and sag terms, against their definitions.

QuadrotorDynamics MismatchHoverDynamics(const QuadrotorDynamicsParams& params, double thrust_N,
                                        const Eigen::Vector3d& v_W, double t_s) {
  control::QuadState state;
  state.t_s = t_s;
  state.p_WB = Eigen::Vector3d(0.0, 0.0, 2.0);
  state.v_W = v_W;
  QuadrotorDynamics vehicle(params, state);
  vehicle.SetMotorCommands(
      Eigen::Vector4d::Constant(params.vehicle.rotor.CommandFromThrust(thrust_N)));
  vehicle.SettleRotors();
  return vehicle;
}

TEST(VehicleMismatch, QuadraticAndThrustDependentDragFollowTheirDefinitions) {
  QuadrotorDynamicsParams params;
  const double hover_N = params.vehicle.mass_kg * params.vehicle.gravity_mps2 / 4.0;
  const Eigen::Vector3d v_W(3.0, 4.0, 0.0);
  // Quadratic only (D = 0): a = -c_q |v| v horizontally.
  params.vehicle.rotor_drag_D_per_s.setZero();
  params.quadratic_drag_per_m = 0.03;
  const QuadrotorDynamics quadratic = MismatchHoverDynamics(params, hover_N, v_W, 0.0);
  EXPECT_LT((quadratic.Acceleration_W().head<2>() - (-0.03 * 5.0 * v_W.head<2>())).norm(), 1e-12);
  // Rotor drag at twice the hover thrust with e = 0.5: D sqrt(2).
  params = QuadrotorDynamicsParams();
  params.drag_thrust_exponent = 0.5;
  const QuadrotorDynamics doubled =
      MismatchHoverDynamics(params, 2.0 * hover_N, Eigen::Vector3d(2.0, 0.0, 0.0), 0.0);
  EXPECT_NEAR(doubled.SpecificForce_B().x(), -0.5 * std::sqrt(2.0) * 2.0, 1e-12);
  // In hover the factor is 1: F.2's D.
  const QuadrotorDynamics hover =
      MismatchHoverDynamics(params, hover_N, Eigen::Vector3d(2.0, 0.0, 0.0), 0.0);
  EXPECT_NEAR(hover.SpecificForce_B().x(), -0.5 * 2.0, 1e-12);
}

TEST(VehicleMismatch, BatterySagScalesTheThrustMapWithTime) {
  QuadrotorDynamicsParams params;
  params.battery_sag_per_s = 0.01;
  const double f_N = 1.2;
  const QuadrotorDynamics later = MismatchHoverDynamics(params, f_N, Eigen::Vector3d::Zero(), 10.0);
  EXPECT_LT((later.RotorThrusts_N() - Eigen::Vector4d::Constant(0.9 * f_N)).norm(), 1e-12);
  // A step of the lag integrates towards the sagged target too.
  QuadrotorDynamics vehicle = MismatchHoverDynamics(params, f_N, Eigen::Vector3d::Zero(), 10.0);
  // Over 0.5 s (>> the time constants) the thrust follows the falling target (1 - s t) f with
  // the down time constant's lag: it reads the target of t = 10.5 s - alpha_dwn.
  vehicle.Step(0.5);
  const double lagged_t_s = 10.5 - params.vehicle.rotor.time_constant_down_s;
  EXPECT_NEAR(vehicle.RotorThrusts_N()[0], (1.0 - 0.01 * lagged_t_s) * f_N, 2e-5);
}

// The LQR's torque estimate eta_hat (RotorThrustEstimator on the nominal model) against the torque
// the mismatched rotors produce for the same commanded thrusts: the difference is what gamma_i,
// the thrust map and the torque map factors imply, (G.1) with f_i -> gamma_i s_f f_i and
// tau_i -> gamma_i s_tau tau(u_i).
TEST(VehicleMismatch, TorqueEstimateErrorIsWhatTheMismatchImplies) {
  const control::VehicleParameters nominal;
  VehicleMismatch m;
  m.thrust_map_factor = 0.8;
  m.torque_map_factor = 1.25;
  m.rotor_fitness_factor = Eigen::Vector4d(1.05, 0.92, 1.0, 0.97);
  QuadrotorDynamicsParams params;
  params.vehicle = MismatchedVehicle(nominal, m);
  QuadrotorDynamics vehicle(params);
  const Eigen::Vector4d f_cmd_N(1.0, 1.3, 0.8, 1.15);
  Eigen::Vector4d u;
  for (int i = 0; i < 4; ++i) u[i] = nominal.rotor.CommandFromThrust(f_cmd_N[i]);
  vehicle.SetMotorCommands(u);  // what the flight controller sends (its inverse map)
  vehicle.SettleRotors();
  control::RotorThrustEstimator estimator(nominal);
  estimator.Reset(f_cmd_N);
  const Eigen::Vector3d error = vehicle.RotorTorque_B() - estimator.BodyTorque_B();
  Eigen::Vector3d implied = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r = nominal.RotorPosition_B(i);
    const double df_N = (m.rotor_fitness_factor[i] * m.thrust_map_factor - 1.0) * f_cmd_N[i];
    implied += Eigen::Vector3d(r.y() * df_N, -r.x() * df_N, 0.0);
    implied.z() += control::VehicleParameters::RotorYawSign(i) *
                   (m.rotor_fitness_factor[i] * m.torque_map_factor - 1.0) *
                   nominal.rotor.DragTorqueFromCommand(u[i]);
  }
  EXPECT_LT((error - implied).norm(), 1e-12) << error.transpose() << " vs " << implied.transpose();
  EXPECT_GT(error.norm(), 0.01);  // a real error, not a vanishing one
}

// ---------------------------------------------------------------------------------------------
// Closed loop.

// The last second of a 6 s hover at the start on a vehicle with the seed's mismatch: mean height
// below the set-point and largest horizontal distance.
struct MismatchedHover {
  VehicleMismatch mismatch;
  double lambda = 1.0;  // CalibrateHoverThrust's factor, 1 uncalibrated
  double dz_m = 0.0;
  double xy_max_m = 0.0;
  double gravity_mps2 = 0.0;
};

MismatchedHover FlyMismatchedHover(std::uint64_t seed, bool calibrated,
                                   double torque_observer_time_constant_s) {
  SitlRunnerParams params = test_support::QuietSitlParams(6.0);
  params.trajectory_decimation = 10;
  params.SetSeed(seed);
  params.flight_controller.low_level.torque_observer_time_constant_s =
      torque_observer_time_constant_s;
  GroundTruthAutopilot autopilot(params.dynamics.vehicle,
                                 test_support::HoverAt(params.initial_state.p_WB));
  MismatchedHover hover;
  hover.mismatch = DrawVehicleMismatch(VehicleMismatchBounds(), seed);
  ApplyVehicleMismatch(hover.mismatch, &params);
  if (calibrated) hover.lambda = CalibrateHoverThrust(hover.mismatch, &params);
  hover.gravity_mps2 = params.dynamics.vehicle.gravity_mps2;
  const SitlResult result = SitlRunner(params, nullptr).Run(autopilot);
  EXPECT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  double dz_sum = 0.0;
  int n = 0;
  for (const control::QuadState& s : result.trajectory) {
    if (s.t_s < 5.0) continue;
    dz_sum += params.initial_state.p_WB.z() - s.p_WB.z();
    hover.xy_max_m = std::max(hover.xy_max_m, s.p_WB.head<2>().norm());
    ++n;
  }
  hover.dz_m = dz_sum / n;
  return hover;
}

// On the thesis' law (no torque observer), a hovering vehicle whose rotor i gives
// s_i = s_f gamma_i (1 - sag t) / lambda times the thrust the flight controller believes
// (lambda = 1 uncalibrated, else CalibrateHoverThrust's): in steady hover each true rotor thrust
// is m g / 4, so the commanded mass-normalized total is g mean(1 / s_i) and the P height loop
// (no integrator) sits dz = g (mean(1 / s_i) - 1) / p_z below the set-point.
TEST(VehicleMismatch, MismatchedVehiclesHoverWithThePredictedHeightOffset) {
  const control::PositionControllerParams gains;
  for (const bool calibrated : {false, true}) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
      const MismatchedHover hover = FlyMismatchedHover(seed, calibrated, 0.0);
      const VehicleMismatch& m = hover.mismatch;
      // Against the prediction at t = 5.5 s, the middle of the averaged second.
      const Eigen::Vector4d s_i =
          m.rotor_fitness_factor *
          (m.thrust_map_factor * (1.0 - m.battery_sag_per_s * 5.5) / hover.lambda);
      const double predicted_dz =
          hover.gravity_mps2 * (s_i.cwiseInverse().mean() - 1.0) / gains.p_z_per_s2;
      // 5 mm: the prediction neglects second-order terms (tilt, kappa(f) varying with thrust).
      EXPECT_NEAR(hover.dz_m, predicted_dz, 5e-3) << "seed " << seed << " calibrated " << calibrated;
      if (calibrated) {
        EXPECT_LT(std::abs(hover.dz_m), 0.01);  // only the sag is left
      }
      // Horizontally only the attitude offset that balances the gamma_i torques (no integrator).
      EXPECT_LT(hover.xy_max_m, 0.15) << "seed " << seed;
    }
  }
}

// The torque-disturbance observer (the SITL missions' default) estimates the gamma_i torques and
// cancels them: the attitude offset and so the horizontal drift of the thesis' law vanish, while
// the collective thrust, and so the height offset, stays what the thesis' law flies.
TEST(VehicleMismatch, TheTorqueObserverRemovesTheAttitudeOffsetOfAMismatchedVehicle) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const MismatchedHover thesis = FlyMismatchedHover(seed, false, 0.0);
    const MismatchedHover observed = FlyMismatchedHover(seed, false, 0.1);
    EXPECT_GT(thesis.xy_max_m, 0.03) << "seed " << seed;  // the offset to remove
    EXPECT_LT(observed.xy_max_m, 0.005) << "seed " << seed;
    // Second order: the rotors' split of the yaw torque moves with their thrusts (kappa(f)).
    EXPECT_NEAR(observed.dz_m, thesis.dz_m, 0.01) << "seed " << seed;
  }
}

// Ground truth recorded by the autopilot at each Step, and rotor thrusts stepped at t = 0.5 s.
class MismatchLatencyProbe : public perception::Autopilot {
 public:
  explicit MismatchLatencyProbe(double hover_N) : hover_N_(hover_N) {}
  std::string name() const override { return "latency_probe"; }
  bool UsesGroundTruth() const override { return true; }
  void OnGroundTruth(const control::QuadState& state) override { state_t_s_ = state.t_s; }
  perception::AutopilotCommand Step(double t_s) override {
    received_.emplace_back(t_s, state_t_s_);
    perception::AutopilotCommand command;
    command.kind = perception::AutopilotCommand::Kind::kRotorThrusts;
    command.rotor_thrusts.thrust_N.setConstant(t_s < 0.5 - 1e-9 ? hover_N_ : 1.1 * hover_N_);
    return command;
  }
  std::vector<std::pair<double, double>> received_;  // (step time, ground truth's time)

 private:
  double hover_N_;
  double state_t_s_ = -1.0;
};

// First time after 0.4 s the vertical speed grows: the thrust step reached the rotors (before,
// the vehicle holds hover thrust; with command latency it fell while the motors idled at first).
double FirstClimbTime(const SitlResult& result) {
  const std::vector<control::QuadState>& x = result.trajectory;
  for (size_t k = 1; k < x.size(); ++k) {
    if (x[k].t_s > 0.4 && x[k].v_W.z() - x[k - 1].v_W.z() > 1e-9) return x[k].t_s;
  }
  return -1.0;
}

TEST(VehicleMismatch, LatenciesDelayTheResponseByTheSetAmount) {
  SitlRunnerParams params = test_support::QuietSitlParams(1.0);
  const double hover_N = params.dynamics.vehicle.mass_kg * params.dynamics.vehicle.gravity_mps2 / 4;
  MismatchLatencyProbe prompt(hover_N);
  const SitlResult reference = SitlRunner(params, nullptr).Run(prompt);
  params.command_latency_s = 0.022;
  params.esc_delay_s = 0.004;
  params.estimate_latency_s = 0.013;
  MismatchLatencyProbe late(hover_N);
  const SitlResult delayed = SitlRunner(params, nullptr).Run(late);
  ASSERT_GT(FirstClimbTime(reference), 0.5);
  EXPECT_NEAR(FirstClimbTime(delayed) - FirstClimbTime(reference), 0.026, 1e-6);
  // The autopilot sees the state of t - 13 ms (the initial state before that).
  for (const auto& [t_s, state_t_s] : late.received_) {
    EXPECT_NEAR(state_t_s, std::max(0.0, t_s - 0.013), 1e-9) << "t = " << t_s;
  }
  for (const auto& [t_s, state_t_s] : prompt.received_) EXPECT_NEAR(state_t_s, t_s, 1e-9);
}

// vehicle.mismatch off is the vehicle = model flight; a mismatch drawn with zero bounds goes
// through every new path (the flight controller's own model, ESC and estimate queues) and must
// reproduce it bit for bit.
TEST(VehicleMismatch, ZeroBoundsReproduceTheModelVehicleBitForBit) {
  TrackingFlightParams params;
  control::CircleTrajectoryParams circle;
  circle.speed_mps = 2.0;
  circle.ramp.ramp_s = 1.0;
  circle.ramp.num_loops = 0.3;
  params.reference = std::make_shared<control::CircleTrajectory>(circle);
  const TrackingFlightResult model = FlyTrackingFlight(params);
  params.vehicle.mismatch = true;
  VehicleMismatchBounds& zero = params.vehicle.mismatch_bounds;
  zero.rotor_drag_relative = zero.thrust_velocity_coeff_kh_max = zero.quadratic_drag_max_per_m =
      zero.drag_thrust_exponent_max = zero.time_constant_relative = zero.thrust_map_relative =
          zero.torque_map_relative = zero.rotor_fitness_relative = zero.battery_sag_max_per_s =
              zero.esc_delay_max_s = zero.gyro_vibration_noise_max = 0.0;
  zero.command_latency_s.setZero();
  zero.estimate_latency_s.setZero();
  const TrackingFlightResult zero_mismatch = FlyTrackingFlight(params);
  ASSERT_EQ(model.sitl.trajectory.size(), zero_mismatch.sitl.trajectory.size());
  for (size_t k = 0; k < model.sitl.trajectory.size(); ++k) {
    const control::QuadState& a = model.sitl.trajectory[k];
    const control::QuadState& b = zero_mismatch.sitl.trajectory[k];
    ASSERT_EQ(a.p_WB, b.p_WB) << "k = " << k;
    ASSERT_EQ(a.q_WB.coeffs(), b.q_WB.coeffs()) << "k = " << k;
    ASSERT_EQ(a.omega_B, b.omega_B) << "k = " << k;
  }
  EXPECT_EQ(model.error.E_a_m, zero_mismatch.error.E_a_m);
  // The default bounds do change the flight.
  params.vehicle.mismatch_bounds = VehicleMismatchBounds();
  EXPECT_NE(FlyTrackingFlight(params).error.E_a_m, model.error.E_a_m);
}

}  // namespace
}  // namespace aperture::sim
