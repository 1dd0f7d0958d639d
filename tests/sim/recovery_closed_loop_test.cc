// Closed-loop recovery after a throw (Faessler thesis B.3, B.4.2): the simulated vehicle
// (sim::QuadrotorDynamics) is held still, then thrown upwards while tumbling, and recovered to a
// position hold by the full on-board chain of paper B, all from simulated sensors:
//   control::RecoveryPipeline: ImuSensor -> LaunchDetector (B.29), ImuAttitudeEstimator
//   (B.22-B.26); RangeSensor + IMU -> HeightFilter (B.27-B.28); RecoveryStateMachine (B.3.2)
//   -> ThrustRatesCommand
//   ProportionalBodyRateController (B.21) -> Mixer (G) -> rotor thrusts -> vehicle.
// The vision pipeline is emulated: its estimate (ground truth in a shifted frame) becomes
// available 1 s after the height stage starts, as SVO initializes during the horizontal drift.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "control/constants.h"
#include "control/mixer.h"
#include "control/proportional_body_rate_controller.h"
#include "control/recovery_pipeline.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture {
namespace {

using control::RecoveryStage;

constexpr double kRecoveryLoopDt_s = 0.002;  // control and IMU period, 500 Hz (B.2.5)
using control::kPi;

struct ThrowCase {
  std::string name;
  Eigen::Quaterniond q_held;        // attitude in the hand
  Eigen::Vector3d v_release_W;      // [m/s]
  Eigen::Vector3d omega_release_B;  // [rad/s]
};

struct RecoveryRun {
  std::vector<control::RecoveryTransition> transitions;
  double min_height_m = 1e9;
  double max_tilt_error_rad = 0.0;         // IMU estimator tilt error after launch
  double max_tumble_tilt_error_rad = 0.0;  // ... during stages 0-1 (gyro-driven)
  double final_tilt_error_rad = 0.0;       // ... at the end (hover)
  double final_tilt_rad = 0.0;
  double final_speed_mps = 0.0;
  double final_position_error_m = 0.0;  // from the locked position (vision frame)
  double final_height_error_m = 0.0;    // height filter vs truth
  double max_tilt_after_launch_rad = 0.0;
};

RecoveryRun Throw(const ThrowCase& c) {
  sim::QuadrotorDynamicsParams sim_params;
  const control::VehicleParameters& vehicle = sim_params.vehicle;
  control::QuadState start;
  start.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  start.q_WB = c.q_held;
  sim::QuadrotorDynamics dynamics(sim_params, start);
  sim::ImuSensorParams imu_params;
  imu_params.latency_s = 0.0;
  sim::ImuSensor imu(imu_params);
  sim::RangeSensor range(sim::RangeSensorParams{});

  control::RecoveryPipeline recovery(vehicle);
  const control::ProportionalBodyRateController rate_controller(vehicle);
  const control::Mixer mixer(vehicle);

  const Eigen::Vector3d vision_offset_W(1.0, -2.0, 0.05);  // vision frame != world frame
  const double t_release = 0.4;
  bool released = false;
  bool vision_ready = false;
  RecoveryRun run;

  for (double t = kRecoveryLoopDt_s; t < 6.0; t += kRecoveryLoopDt_s) {
    if (!released && t >= t_release) {
      released = true;
      dynamics.ApplyImpulse(vehicle.mass_kg * c.v_release_W, vehicle.Inertia() * c.omega_release_B);
    }
    if (released) dynamics.Step(kRecoveryLoopDt_s);  // in the hand the vehicle does not move
    const control::QuadState& truth = dynamics.state();
    const Eigen::Vector3d f_B =
        released
            ? dynamics.SpecificForce_B()
            : Eigen::Vector3d(truth.q_WB.conjugate() * Eigen::Vector3d(0, 0, vehicle.gravity_mps2));
    for (const perception::ImuSample& sample : imu.Update(t, f_B, truth.omega_B)) {
      recovery.AddImu(sample.t_s, sample.specific_force_B, sample.omega_B);
    }
    if (const auto reading = range.Update(truth); reading && reading->valid) {
      recovery.AddRange(reading->range_m);
    }
    const control::RecoveryStateMachine& machine = recovery.state_machine();
    vision_ready = vision_ready || (machine.stage() == RecoveryStage::kHeight &&
                                    t - machine.stage_entry_time_s() >= 1.0 - 1e-9);
    if (vision_ready) {
      control::QuadState vision = truth;
      vision.p_WB += vision_offset_W;
      recovery.SetVisionState(vision);
    }
    const control::RecoveryOutput out = recovery.Step(t);
    const Eigen::Vector3d omega_hat_B = recovery.attitude().omega_B();

    // Low-level loop (B.21) and mixer; the rotors idle before the launch.
    const Eigen::Vector3d torque_B =
        rate_controller.ComputeTorque(out.command.omega_des_B, omega_hat_B);
    dynamics.SetRotorThrustCommand(
        mixer
            .Mix(out.stage == RecoveryStage::kWaitingForLaunch ? Eigen::Vector3d::Zero() : torque_B,
                 out.command.collective_thrust_mps2)
            .command);

    if (recovery.launch_detector().launched()) {
      const Eigen::Vector3d up_true = truth.q_WB.conjugate() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d up_est =
          recovery.attitude().q_WB().conjugate() * Eigen::Vector3d::UnitZ();
      const double e = std::acos(std::clamp(up_true.dot(up_est), -1.0, 1.0));
      if (recovery.state_machine().stage() <= RecoveryStage::kAttitude) {
        run.max_tumble_tilt_error_rad = std::max(run.max_tumble_tilt_error_rad, e);
      }
      run.max_tilt_error_rad = std::max(run.max_tilt_error_rad, e);
      run.final_tilt_error_rad = e;
      run.max_tilt_after_launch_rad =
          std::max(run.max_tilt_after_launch_rad,
                   std::acos(std::clamp((truth.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)));
    }
    run.min_height_m = std::min(run.min_height_m, truth.p_WB.z());
  }
  const control::QuadState& truth = dynamics.state();
  run.transitions = recovery.state_machine().transitions();
  run.final_tilt_rad =
      std::acos(std::clamp((truth.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
  run.final_speed_mps = truth.v_W.norm();
  run.final_position_error_m =
      (truth.p_WB + vision_offset_W - recovery.state_machine().locked_position_W()).norm();
  run.final_height_error_m = recovery.height_filter().estimate().z_m - truth.p_WB.z();
  return run;
}

class RecoveryClosedLoop : public ::testing::TestWithParam<ThrowCase> {};

TEST_P(RecoveryClosedLoop, ThrownVehicleReachesPositionHold) {
  const RecoveryRun run = Throw(GetParam());
  // Every stage in order, none skipped (B.3.2).
  ASSERT_EQ(run.transitions.size(), 5u);
  std::string log;
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(static_cast<int>(run.transitions[k].to), k + 1);
    log += std::string(control::ToString(run.transitions[k].to)) + "@" +
           std::to_string(run.transitions[k].t_s) + " ";
  }
  RecordProperty("stage_entries", log);
  RecordProperty("max_tilt_after_launch_deg",
                 std::to_string(run.max_tilt_after_launch_rad * 180 / kPi));
  RecordProperty("max_estimator_tilt_error_deg",
                 std::to_string(run.max_tilt_error_rad * 180 / kPi));
  RecordProperty("min_height_m", std::to_string(run.min_height_m));
  RecordProperty("final_position_error_m", std::to_string(run.final_position_error_m));
  // Launch detected within the 50 ms window after release at 0.4 s (B.29).
  EXPECT_GT(run.transitions[0].t_s, 0.4);
  EXPECT_LT(run.transitions[0].t_s, 0.4 + 0.06);
  // The throw reaches the scenario's attitude (upside-down or close to it).
  EXPECT_GT(run.max_tilt_after_launch_rad, 0.75 * kPi);
  // Recovered well above the ground, and holding position in the last stage.
  EXPECT_GT(run.min_height_m, 0.5);
  EXPECT_LT(run.transitions[4].t_s, 4.0);
  // After >= 2 s of position control: level (< 2 deg), still (< 5 cm/s), near the lock
  // (< 5 cm; the vehicle settles with the (B.8) gains' ~0.5 s time constants).
  EXPECT_LT(run.final_tilt_rad, 2.0 * kPi / 180.0);
  EXPECT_LT(run.final_speed_mps, 0.05);
  EXPECT_LT(run.final_position_error_m, 0.05);
  RecordProperty("max_tumble_estimator_tilt_error_deg",
                 std::to_string(run.max_tumble_tilt_error_rad * 180 / kPi));
  RecordProperty("final_estimator_tilt_error_deg",
                 std::to_string(run.final_tilt_error_rad * 180 / kPi));
  // Through the tumble the IMU-only estimate is carried by the gyro (B.22; the update gate is
  // closed above 0.5 rad/s): exact for constant rates, so the zero-order hold under the
  // controller's angular accelerations of several hundred rad/s^2 (~0.5 alpha dt^2 per step),
  // and gated-in updates at the end of stage 1, where c = g makes |f| ~ g while f is along z_B,
  // remain. Measured 1.7 and 2.2 deg; bound 3 deg.
  EXPECT_LT(run.max_tumble_tilt_error_rad, 3.0 * kPi / 180.0);
  // In flight the accelerometer measures thrust + rotor drag, not -g: tilt is observable only
  // through the drag term (B.2.5: "does not drift ... because of aerodynamic effects"). While the
  // vehicle drifts and brakes in stages 2-4 the error grows (measured up to 17 deg in the
  // upside-down case; recorded, not bounded here) and in the final hover it re-converges slowly
  // through the drag coupling: measured 0.08 and 0.75 deg after 4 s; bound 1.5 deg.
  EXPECT_LT(run.final_tilt_error_rad, 1.5 * kPi / 180.0);
  // Height filter vs truth at the end: within the range noise scale.
  EXPECT_LT(std::abs(run.final_height_error_m), 0.03);
}

INSTANTIATE_TEST_SUITE_P(
    Throws, RecoveryClosedLoop,
    ::testing::Values(ThrowCase{"held_level_tossed_with_flip", Eigen::Quaterniond::Identity(),
                                Eigen::Vector3d(2.0, 1.0, 4.0), Eigen::Vector3d(18.0, -4.0, 3.0)},
                      ThrowCase{"held_upside_down",
                                Eigen::Quaterniond(Eigen::AngleAxisd(0.9 * kPi,
                                                                     Eigen::Vector3d::UnitY())),
                                Eigen::Vector3d(-1.5, 2.5, 3.0), Eigen::Vector3d(-3.0, 5.0, -6.0)}),
    [](const ::testing::TestParamInfo<ThrowCase>& info) { return info.param.name; });

}  // namespace
}  // namespace aperture
