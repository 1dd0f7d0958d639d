#include "experiments/gap/gap_trial_config.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::experiments {
namespace {

void RequireRange(const Eigen::Vector2d& range, const std::string& field) {
  control::Require(range.allFinite() && range.x() >= 0.0 && range.x() <= range.y(),
                   std::string("GapTrialRanges.") + field,
                   "must be a finite range [min, max] with 0 <= min <= max");
}

// SplitMix64 finalizer: adjacent (seed, index) pairs give uncorrelated trial seeds.
std::uint64_t Mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

void GapTrialRanges::Validate() const {
  control::Require(std::isfinite(max_roll_deg) && max_roll_deg >= 0.0 && max_roll_deg < 90.0,
                   "GapTrialRanges.max_roll_deg", "must be in [0, 90) deg");
  control::Require(
      std::isfinite(min_roll_deg) && min_roll_deg >= 0.0 && min_roll_deg <= max_roll_deg,
      "GapTrialRanges.min_roll_deg", "must be in [0, max_roll_deg] deg");
  control::Require(std::isfinite(max_pitch_deg) && max_pitch_deg >= 0.0 && max_pitch_deg < 90.0,
                   "GapTrialRanges.max_pitch_deg", "must be in [0, 90) deg");
  control::Require(start_offset_m.allFinite() && (start_offset_m.array() >= 0.0).all(),
                   "GapTrialRanges.start_offset_m", "must be finite and >= 0");
  control::Require(std::isfinite(max_start_yaw_deg) && max_start_yaw_deg >= 0.0,
                   "GapTrialRanges.max_start_yaw_deg", "must be finite and >= 0");
  RequireRange(imu_noise_scale, "imu_noise_scale");
  control::Require(std::isfinite(accel_bias_sigma_mps2) && accel_bias_sigma_mps2 >= 0.0,
                   "GapTrialRanges.accel_bias_sigma_mps2", "must be finite and >= 0");
  control::Require(std::isfinite(gyro_bias_sigma_radps) && gyro_bias_sigma_radps >= 0.0,
                   "GapTrialRanges.gyro_bias_sigma_radps", "must be finite and >= 0");
  control::Require(std::isfinite(max_drop_probability) && max_drop_probability >= 0.0 &&
                       max_drop_probability < 1.0,
                   "GapTrialRanges.max_drop_probability", "must be in [0, 1)");
  RequireRange(exposure_s, "exposure_s");
  control::Require(motion_blur_subframes >= 1, "GapTrialRanges.motion_blur_subframes",
                   "must be >= 1");
}

GapTrialConfig DrawGapTrial(const GapTrialRanges& ranges, std::uint64_t bench_seed, int index,
                            const Eigen::Vector3d& nominal_start_p_W) {
  ranges.Validate();
  if (index < 0) {
    throw std::invalid_argument("DrawGapTrial: trial index " + std::to_string(index) +
                                " must be >= 0");
  }
  GapTrialConfig trial;
  trial.index = index;
  trial.seed = Mix(Mix(bench_seed) ^ static_cast<std::uint64_t>(index));
  // Draws in a fixed order from the trial's own generator (std::uniform_real_distribution's
  // algorithm is fixed by libstdc++ for mt19937_64, so a seed gives the same trial everywhere
  // this project builds).
  std::mt19937_64 rng(Mix(trial.seed ^ 0x6761705F62656E63ull));  // "gap_benc"
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  trial.roll_deg = uniform(ranges.min_roll_deg, ranges.max_roll_deg);
  trial.pitch_deg = uniform(0.0, ranges.max_pitch_deg);
  for (int i = 0; i < 3; ++i) {
    trial.start_p_W(i) =
        nominal_start_p_W(i) + uniform(-ranges.start_offset_m(i), ranges.start_offset_m(i));
  }
  trial.start_yaw_deg = uniform(-ranges.max_start_yaw_deg, ranges.max_start_yaw_deg);
  trial.imu_noise_scale = uniform(ranges.imu_noise_scale.x(), ranges.imu_noise_scale.y());
  for (int i = 0; i < 3; ++i) trial.accel_bias_B(i) = ranges.accel_bias_sigma_mps2 * normal(rng);
  for (int i = 0; i < 3; ++i) trial.gyro_bias_B(i) = ranges.gyro_bias_sigma_radps * normal(rng);
  trial.drop_probability = uniform(0.0, ranges.max_drop_probability);
  trial.exposure_s = uniform(ranges.exposure_s.x(), ranges.exposure_s.y());
  trial.motion_blur_subframes = ranges.motion_blur_subframes;
  return trial;
}

void ApplyGapTrial(const GapTrialConfig& trial, sim::ScenarioParams* params) {
  params->seed = trial.seed;
  params->gap.roll_deg = trial.roll_deg;
  params->gap.pitch_deg = trial.pitch_deg;
  params->vehicle_start.p_m = trial.start_p_W;
  params->vehicle_start.rpy_deg = Eigen::Vector3d(0.0, 0.0, trial.start_yaw_deg);
  for (auto& [name, camera] : params->cameras) {
    camera.exposure_s = trial.exposure_s;
    camera.motion_blur_subframes = trial.motion_blur_subframes;
  }
}

void ApplyGapTrial(const GapTrialConfig& trial, sim::SitlRunnerParams* params) {
  params->SetSeed(trial.seed);
  sim::ImuSensorParams& imu = params->imu;
  imu.ScaleNoise(trial.imu_noise_scale);
  imu.accel_bias_initial_B = trial.accel_bias_B;
  imu.gyro_bias_initial_B = trial.gyro_bias_B;
  for (sim::SitlCamera& camera : params->cameras) camera.drop_probability = trial.drop_probability;
}

}  // namespace aperture::experiments
