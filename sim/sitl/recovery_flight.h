#pragma once
// One hand throw recovered in the SITL (Faessler thesis B.4: "throw it in the air ... attitude up
// to upside-down, velocities of several m/s"). The hand is kinematic: before the release at t = 0
// the autopilot receives the IMU samples of the vehicle held still for held_s (the attitude
// estimator settles on gravity, as on the real vehicle) and then thrown for throw_s
// (HandMotionAt: the hand's acceleration, up to ~25 m/s^2 as in B.4.2, and rotation, which the
// launch detector must not take for free fall); then the SITL starts at the release with the
// throw's attitude, velocity, body rates and idling motors;
// RecoveryAutopilot flies it from the noisy IMU and range sensor through the five stages of B.3.2
// while the flight controller runs the configured body-rate law and mixer at 1 kHz. The flight ends
// 'recovered' when the position stage has held for the autopilot's hold_s, 'crashed' on a collision
// (ground), else 'timeout'.
//
//   RecoveryFlightParams params;
//   params.hand_throw = SampleHandThrow(seed);
//   RecoveryFlightResult flight = FlyRecoveryFlight(params);
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "control/recovery_state_machine.h"
#include "sim/control_params_io.h"
#include "sim/sitl/recovery_autopilot.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::sim {

struct HandThrow {
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  // attitude at release
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             // [m/s]
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();         // [rad/s]
};

// Ranges of SampleHandThrow; defaults as in B.4 (up to upside-down, several m/s, tumbling).
struct HandThrowRanges {
  double max_tilt_rad = 3.14159265358979323846;  // tilt uniform in [0, max]: up to upside-down
  double max_horizontal_speed_mps = 3.0;         // uniform in [0, max], random direction
  double min_up_speed_mps = 1.0;                 // thrown upwards, uniform in [min, max]
  double max_up_speed_mps = 4.0;
  double max_rate_radps = 15.0;  // |omega| uniform in [0, max], random direction
};

// A random throw from `seed` (deterministic): random heading, tilt about a random horizontal axis.
HandThrow SampleHandThrow(std::uint64_t seed, const HandThrowRanges& ranges = {});

// The hand's throw at t_s in [-throw_s, 0] (release at 0): the velocity rises from rest to the
// release velocity on a minimum-jerk profile (peak acceleration 1.875 |v| / throw_s), the body
// rates ramp linearly from 0 to the release rates about their (fixed) body axis, ending at the
// release attitude. throw_s = 0: the release attitude, no motion.
struct HandMotion {
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();      // [m/s^2]
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();  // [rad/s]
};
HandMotion HandMotionAt(const HandThrow& hand_throw, double throw_s, double t_s);

struct RecoveryFlightParams {
  HandThrow hand_throw;
  Eigen::Vector3d p_release_W{0.0, 0.0, 1.5};  // release point [m] (hand height)
  double held_s = 0.5;                         // held still in the hand before the throw [s]
  double throw_s = 0.25;       // the throw's motion in the hand, ending at the release [s]
  ControlStackParams control;  // flight controller: body-rate law, mixer, saturation
  RecoveryAutopilotParams autopilot;
  QuadrotorDynamicsParams dynamics;
  ImuSensorParams imu;
  RangeSensorParams range;
  // vehicle.mismatch: the simulated vehicle departs from `dynamics` (the controllers' model) by a
  // VehicleMismatch drawn from `seed` (sim/sitl/vehicle_mismatch.h).
  VehicleMismatchParams vehicle;
  std::uint64_t seed = 1;    // sensor noise (SitlRunnerParams::SetSeed), the vehicle's draw
  double duration_s = 10.0;  // timeout [s]
  int trajectory_decimation = 10;
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

struct RecoveryFlightResult {
  SitlResult sitl;
  std::string outcome;  // "recovered", "crashed", "timeout"
  std::vector<control::RecoveryTransition> transitions;
  double vision_available_s = -1.0;  // the vision pipeline's initialization (< 0: never)
  // When the launch detector fired (B.29; the release is at 0, the hand's throw before it) [s];
  // NaN if it never did.
  double launch_detected_s = 0.0;
  double min_height_m = 0.0;    // lowest ground-truth height [m]
  double final_tilt_rad = 0.0;  // angle between z_B and z_W at the end
  double final_speed_mps = 0.0;
  bool recovered() const { return outcome == "recovered"; }
};

RecoveryFlightResult FlyRecoveryFlight(const RecoveryFlightParams& params);

}  // namespace aperture::sim
