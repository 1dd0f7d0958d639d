#pragma once
// Test support: SITL parameters with noise-free sensors (the IMU exact, no biases), starting at
// rest 1.5 m above the origin, so closed-loop tests see only the effect they isolate; and a
// hover on ground truth.
#include <Eigen/Core>

#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::test_support {

inline sim::SitlRunnerParams QuietSitlParams(double duration_s) {
  sim::SitlRunnerParams params;
  params.duration_s = duration_s;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  params.imu.accel_noise_density = 0.0;
  params.imu.gyro_noise_density = 0.0;
  params.imu.accel_bias_random_walk = 0.0;
  params.imu.gyro_bias_random_walk = 0.0;
  return params;
}

// The ground-truth autopilot holding one waypoint: position p_W, yaw 0, no dwell.
inline sim::GroundTruthAutopilotParams HoverAt(const Eigen::Vector3d& p_W) {
  sim::GroundTruthAutopilotParams params;
  params.waypoints.push_back(sim::Waypoint{p_W, 0.0, 0.0});
  return params;
}

}  // namespace aperture::test_support
