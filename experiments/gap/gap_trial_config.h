#pragma once
// One randomized trial of `aperture bench gap` (seed 000 Sec. IV-B analog): the gap inclination,
// the vehicle's start pose, the IMU's noise and biases, the camera's frame drops (detection
// dropouts) and exposure (motion blur). A trial is a pure function of (bench seed, trial index),
// so results do not depend on the order or the thread that runs the trials.
//
//   GapTrialRanges ranges;                              // paper: roll 0-45 deg, pitch 0-30 deg
//   GapTrialConfig trial = DrawGapTrial(ranges, seed, i);
//   ApplyGapTrial(trial, &scenario_params);             // before BuildScenario
//   ApplyGapTrial(trial, &sitl_params);                 // after ConfigureSitlFromScenario
#include <Eigen/Core>
#include <cstdint>

#include "sim/scenario/scenario_params.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

// Ranges the trials are drawn from (uniform unless noted). Defaults: the inclinations of the
// paper's 35 flights; the rest is what a real flight varies by.
struct GapTrialRanges {
  double min_roll_deg = 0.0;    // gap roll about x_W, uniform in [min, max]
  double max_roll_deg = 45.0;
  double max_pitch_deg = 30.0;  // gap pitch about y_W, uniform in [0, max]
  // Start position: the scenario's vehicle.start plus a uniform offset in [-r, r] per axis [m];
  // 0.5 m laterally keeps the gap (5 m ahead) well inside the fisheye's view.
  Eigen::Vector3d start_offset_m = Eigen::Vector3d(0.5, 0.5, 0.3);
  double max_start_yaw_deg = 10.0;  // start yaw uniform in [-max, max]
  // IMU white-noise densities and bias random walks (sim::ImuSensorParams defaults, an
  // MPU-6000-class IMU) are scaled by one factor uniform in this range.
  Eigen::Vector2d imu_noise_scale = Eigen::Vector2d(0.5, 2.0);
  // Turn-on biases, Gaussian per axis: the order of an uncalibrated MEMS IMU after a
  // factory calibration (accelerometer ~5 mg, gyro ~0.3 deg/s).
  double accel_bias_sigma_mps2 = 0.05;
  double gyro_bias_sigma_radps = 0.005;
  // Camera frame-drop probability uniform in [0, max]: each drop is a missed detection.
  double max_drop_probability = 0.2;
  // Exposure uniform in this range [s] with motion_blur_subframes renders per frame: at the
  // traverse's ~400 deg/s, 4 ms smear edges by ~7 px on the 180 deg fisheye.
  Eigen::Vector2d exposure_s = Eigen::Vector2d(0.5e-3, 4.0e-3);
  // Renders per frame (1 = no blur, the exposure is then only recorded); each costs a render.
  int motion_blur_subframes = 3;

  // Throws std::invalid_argument naming the field for negative or non-finite values, inverted
  // ranges (min_roll_deg > max_roll_deg too), a drop probability outside [0, 1) or
  // motion_blur_subframes < 1.
  void Validate() const;
};

struct GapTrialConfig {
  int index = 0;
  std::uint64_t seed = 0;  // seeds the scenario (textures, camera noise) and every SITL stream
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  Eigen::Vector3d start_p_W = Eigen::Vector3d::Zero();  // [m]
  double start_yaw_deg = 0.0;
  double imu_noise_scale = 1.0;
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();   // [rad/s]
  double drop_probability = 0.0;
  double exposure_s = 0.0;
  int motion_blur_subframes = 1;
};

// The trial `index` of a bench run with `bench_seed`; `nominal_start_p_W` is the scenario's
// vehicle.start. Throws std::invalid_argument for invalid ranges or a negative index.
GapTrialConfig DrawGapTrial(const GapTrialRanges& ranges, std::uint64_t bench_seed, int index,
                            const Eigen::Vector3d& nominal_start_p_W);

// Scenario side: seed, gap roll/pitch, vehicle start pose, every camera's exposure and blur.
void ApplyGapTrial(const GapTrialConfig& trial, sim::ScenarioParams* params);
// SITL side: every random stream from trial.seed (SetSeed), IMU noise scale and initial biases
// (scaling the densities already in params->imu), every camera's drop probability. Call after
// sim::ConfigureSitlFromScenario.
void ApplyGapTrial(const GapTrialConfig& trial, sim::SitlRunnerParams* params);

}  // namespace aperture::experiments
