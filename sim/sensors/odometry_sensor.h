#pragma once
// Simulated odometry source: body poses T_WB at a fixed rate with white noise, standing in for
// what a vehicle's own odometry delivers (a VIO, or seed 003's optical-flow + IMU EKF on the
// AR.Drone, whose Table III spread is a few cm). Each measurement is
//   p = p_WB + n_p,  n_p ~ N(0, position_sigma_m^2 I)   (W)
//   R = R_WB Exp(n_theta),  n_theta ~ N(0, rotation_sigma_rad^2 I)   (B, right perturbation)
// as a perception::PoseMeasurement of X = B with exactly that covariance, so a pose + IMU filter
// (perception::PoseFusion) fuses it. Drift is not modelled: the noise is white, the error does
// not grow with distance (say so when comparing with a VIO). Deterministic for a given seed.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>

#include "control/quad_state.h"
#include "perception/estimation/pose_imu_filter.h"
#include "sim/sensors/sample_schedule.h"

namespace aperture::sim {

struct OdometrySensorParams {
  double rate_hz = 50.0;  // a VIO's output rate
  // 2 cm and 0.5 deg: the spread of a VIO over a few metres, within seed 003's Table III.
  double position_sigma_m = 0.02;
  double rotation_sigma_rad = 0.0087;
  std::uint64_t seed = 5;

  void Validate() const;  // throws std::invalid_argument naming the field
};

class OdometrySensor {
 public:
  explicit OdometrySensor(const OdometrySensorParams& params);

  // Call with the true state at each step (non-decreasing state.t_s); returns a measurement
  // stamped state.t_s when one is due.
  std::optional<perception::PoseMeasurement> Update(const control::QuadState& state);

 private:
  Eigen::Vector3d GaussianVector(double sigma);

  OdometrySensorParams params_;
  SampleSchedule schedule_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace aperture::sim
