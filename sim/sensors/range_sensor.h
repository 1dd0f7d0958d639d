#pragma once
// Simulated downward range sensor (ToF / lidar altimeter) mounted at p_BS in B, measuring along
// -z_B to the nearest surface of its RangeWorld: the ground plane z_W = ground_height_m and, when
// a scene is given, the scene's objects (boxes, tables, a gap frame below the vehicle) except
// those it is told to look through (parts of the vehicle itself). Over the bare ground, a sensor
// at height h whose ray makes the angle theta with -z_W reads h / cos(theta). The reading is
// invalid (valid == false, range_m = 0) when the tilt exceeds max_tilt_rad, the sensor is at or
// below the ground, or the true range is outside [min_range_m, max_range_m]; valid readings carry
// Gaussian noise. Deterministic for a given seed.
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "control/quad_state.h"
#include "perception/sensor_data.h"
#include "sim/scene/scene.h"
#include "sim/sensors/sample_schedule.h"

namespace aperture::sim {

// Defaults: a TeraRanger-One-class ToF rangefinder (0.2-14 m, a few cm accuracy) on a small
// quadrotor; beyond ~30 deg tilt such sensors lose the return on most ground textures.
struct RangeSensorParams {
  double rate_hz = 100.0;
  double min_range_m = 0.2;
  double max_range_m = 14.0;
  double noise_sigma_m = 0.02;           // white noise on valid readings
  double max_tilt_rad = 0.5235987755982988;  // 30 deg between the ray and -z_W
  Eigen::Vector3d p_BS = Eigen::Vector3d::Zero();  // sensor origin in B [m]
  std::uint64_t seed = 2;

  // Throws std::invalid_argument naming the field (rate_hz <= 0, min_range_m < 0,
  // max_range_m <= min_range_m, noise_sigma_m < 0, max_tilt_rad outside (0, pi/2), non-finite).
  void Validate() const;
};

// What a range ray can hit. `scene` (may be null: the ground plane only) must outlive its use.
struct RangeWorld {
  double ground_height_m = 0.0;
  const Scene* scene = nullptr;
  std::vector<int> see_through_object_ids;  // e.g. objects attached to the vehicle body
};

class RangeSensor {
 public:
  explicit RangeSensor(const RangeSensorParams& params, RangeWorld world = {});

  // Reading at state.t_s regardless of the rate.
  perception::RangeReading Measure(const control::QuadState& state);
  // Call once per simulation step; returns a reading when one is due at the sensor rate.
  std::optional<perception::RangeReading> Update(const control::QuadState& state);

  const RangeSensorParams& params() const { return params_; }

 private:
  RangeSensorParams params_;
  RangeWorld world_;
  SampleSchedule schedule_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace aperture::sim
