#include "sim/sitl/recovery_flight.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "control/constants.h"
#include "sim/sensors/imu_sensor.h"

namespace aperture::sim {

HandThrow SampleHandThrow(std::uint64_t seed, const HandThrowRanges& ranges) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  using control::kPi;
  const auto random_direction = [&] {
    // Uniform on the sphere: z uniform in [-1, 1], azimuth uniform.
    const double z = 2.0 * unit(rng) - 1.0;
    const double azimuth = 2.0 * kPi * unit(rng);
    const double r = std::sqrt(1.0 - z * z);
    return Eigen::Vector3d(r * std::cos(azimuth), r * std::sin(azimuth), z);
  };
  HandThrow hand_throw;
  const double heading = 2.0 * kPi * unit(rng);
  const double tilt_axis = 2.0 * kPi * unit(rng);
  const double tilt = ranges.max_tilt_rad * unit(rng);
  hand_throw.q_WB =
      Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(tilt_axis), std::sin(tilt_axis), 0.0)) *
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ());
  const double speed_xy = ranges.max_horizontal_speed_mps * unit(rng);
  const double direction_xy = 2.0 * kPi * unit(rng);
  hand_throw.v_W = Eigen::Vector3d(
      speed_xy * std::cos(direction_xy), speed_xy * std::sin(direction_xy),
      ranges.min_up_speed_mps + (ranges.max_up_speed_mps - ranges.min_up_speed_mps) * unit(rng));
  hand_throw.omega_B = ranges.max_rate_radps * unit(rng) * random_direction();
  return hand_throw;
}

HandMotion HandMotionAt(const HandThrow& hand_throw, double throw_s, double t_s) {
  HandMotion motion;
  if (throw_s <= 0.0) {
    motion.q_WB = hand_throw.q_WB;
    return motion;
  }
  const double u = std::clamp((t_s + throw_s) / throw_s, 0.0, 1.0);
  // Minimum-jerk velocity v = v_release (10u^3 - 15u^4 + 6u^5): a = 30 v_release u^2 (1-u)^2 / T.
  motion.a_W = hand_throw.v_W * 30.0 * u * u * (1.0 - u) * (1.0 - u) / throw_s;
  // omega_B = u omega_release about the fixed body axis: the rotation left until the release is
  // |omega| T (1 - u^2) / 2.
  const double rate_radps = hand_throw.omega_B.norm();
  motion.omega_B = u * hand_throw.omega_B;
  motion.q_WB = hand_throw.q_WB;
  if (rate_radps > 0.0) {
    motion.q_WB = hand_throw.q_WB * Eigen::AngleAxisd(-rate_radps * throw_s * (1.0 - u * u) / 2.0,
                                                      hand_throw.omega_B / rate_radps);
  }
  return motion;
}

void RecoveryFlightParams::Validate() const {
  if (!p_release_W.allFinite() || !hand_throw.v_W.allFinite() || !hand_throw.omega_B.allFinite() ||
      !hand_throw.q_WB.coeffs().allFinite()) {
    throw std::invalid_argument("RecoveryFlightParams: release point and throw must be finite");
  }
  if (!std::isfinite(held_s) || held_s < 0.0) {
    throw std::invalid_argument("RecoveryFlightParams.held_s must be finite and >= 0");
  }
  if (!std::isfinite(throw_s) || throw_s < 0.0) {
    throw std::invalid_argument("RecoveryFlightParams.throw_s must be finite and >= 0");
  }
  if (!std::isfinite(duration_s) || duration_s <= 0.0) {
    throw std::invalid_argument("RecoveryFlightParams.duration_s must be positive");
  }
  control.Validate();
  autopilot.Validate();
}

RecoveryFlightResult FlyRecoveryFlight(const RecoveryFlightParams& params) {
  params.Validate();
  SitlRunnerParams sitl;
  sitl.duration_s = params.duration_s;
  sitl.dynamics = params.dynamics;
  sitl.imu = params.imu;
  sitl.range = params.range;
  sitl.range_enabled = true;
  sitl.flight_controller.low_level = params.control.low_level;
  sitl.trajectory_decimation = params.trajectory_decimation;
  sitl.start_hovering = false;  // motors idle in the hand
  sitl.initial_state.p_WB = params.p_release_W;
  sitl.initial_state.q_WB = params.hand_throw.q_WB.normalized();
  sitl.initial_state.v_W = params.hand_throw.v_W;
  sitl.initial_state.omega_B = params.hand_throw.omega_B;
  sitl.SetSeed(params.seed);
  ApplyVehicleMismatch(params.vehicle, params.seed, &sitl);

  RecoveryAutopilotParams autopilot_params = params.autopilot;
  autopilot_params.vision_seed = params.seed * 7919 + 3;
  RecoveryAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  // In the hand, t in [-held_s - throw_s, 0): held still, then thrown (HandMotionAt); the
  // accelerometer measures the hand's acceleration and the reaction to gravity. A separate noise
  // stream (seed + 1), the same sensor model and rate as the SITL's IMU.
  ImuSensorParams held_imu = sitl.imu;
  held_imu.seed = sitl.imu.seed + 1;
  held_imu.gyro_noise_density = params.imu.gyro_noise_density;  // motors off: no vibration
  ImuSensor hand_imu(held_imu);
  const Eigen::Vector3d g_W(0.0, 0.0, params.dynamics.vehicle.gravity_mps2);
  const double dt_s = 1.0 / sitl.dynamics_rate_hz;
  const HandThrow release{sitl.initial_state.q_WB, params.hand_throw.v_W,
                          params.hand_throw.omega_B};
  for (int k = static_cast<int>(std::ceil((params.held_s + params.throw_s) / dt_s)); k >= 1; --k) {
    const HandMotion hand = HandMotionAt(release, params.throw_s, -k * dt_s);
    for (const perception::ImuSample& sample :
         hand_imu.Update(-k * dt_s, hand.q_WB.conjugate() * (hand.a_W + g_W), hand.omega_B)) {
      autopilot.OnImu(sample);
    }
  }
  SitlRunner runner(sitl, nullptr);
  RecoveryFlightResult result;
  result.sitl = runner.Run(autopilot);
  result.transitions = autopilot.pipeline().state_machine().transitions();
  result.vision_available_s = autopilot.vision_available_s();
  const control::LaunchDetector& launch = autopilot.pipeline().launch_detector();
  result.launch_detected_s =
      launch.launched() ? launch.launch_time_s() : std::numeric_limits<double>::quiet_NaN();
  result.outcome = result.sitl.outcome == SitlResult::Outcome::kCollision       ? "crashed"
                   : result.sitl.outcome == SitlResult::Outcome::kAutopilotDone ? "recovered"
                                                                                : "timeout";
  result.min_height_m = params.p_release_W.z();
  for (const control::QuadState& s : result.sitl.trajectory) {
    result.min_height_m = std::min(result.min_height_m, s.p_WB.z());
  }
  const control::QuadState& last = result.sitl.trajectory.back();
  result.final_tilt_rad =
      std::acos(std::clamp((last.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
  result.final_speed_mps = last.v_W.norm();
  return result;
}

}  // namespace aperture::sim
