#include "sim/sensors/range_sensor.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace aperture::sim {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

const RangeSensorParams& Validated(const RangeSensorParams& params) {
  params.Validate();
  return params;
}

}  // namespace

void RangeSensorParams::Validate() const {
  const auto fail = [](const std::string& field, double value, const std::string& rule) {
    throw std::invalid_argument("RangeSensorParams." + field + " must be " + rule + ", got " +
                                std::to_string(value));
  };
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) fail("rate_hz", rate_hz, "> 0");
  if (!(std::isfinite(min_range_m) && min_range_m >= 0.0)) fail("min_range_m", min_range_m, ">= 0");
  if (!(std::isfinite(max_range_m) && max_range_m > min_range_m)) {
    fail("max_range_m", max_range_m, "finite and > min_range_m");
  }
  if (!(std::isfinite(noise_sigma_m) && noise_sigma_m >= 0.0)) fail("noise_sigma_m", noise_sigma_m, ">= 0");
  if (!(max_tilt_rad > 0.0 && max_tilt_rad < kHalfPi)) fail("max_tilt_rad", max_tilt_rad, "in (0, pi/2)");
  if (!p_BS.allFinite()) throw std::invalid_argument("RangeSensorParams.p_BS must be finite");
}

RangeSensor::RangeSensor(const RangeSensorParams& params, RangeWorld world)
    : params_(Validated(params)),
      world_(std::move(world)),
      schedule_(params_.rate_hz),
      rng_(params_.seed) {
  if (!std::isfinite(world_.ground_height_m)) {
    throw std::invalid_argument("RangeSensor: RangeWorld.ground_height_m must be finite");
  }
}

perception::RangeReading RangeSensor::Measure(const control::QuadState& state) {
  if (!state.IsValid()) throw std::invalid_argument("RangeSensor::Measure: state is not valid");
  perception::RangeReading reading;
  reading.t_s = state.t_s;
  const Eigen::Matrix3d R_WB = state.q_WB.toRotationMatrix();
  const Eigen::Vector3d p_WS = state.p_WB + R_WB * params_.p_BS;
  const double cos_tilt = R_WB(2, 2);  // -z_B . -z_W
  // Drawn for every reading so the noise sequence does not depend on validity.
  const double noise_m = params_.noise_sigma_m * normal_(rng_);
  const double height_m = p_WS.z() - world_.ground_height_m;
  if (cos_tilt < std::cos(params_.max_tilt_rad) || height_m <= 0.0) return reading;
  double range_m = height_m / cos_tilt;
  if (world_.scene != nullptr) {
    if (const std::optional<Hit> hit = world_.scene->Intersect(
            p_WS, -R_WB.col(2), 0.0, range_m, world_.see_through_object_ids)) {
      range_m = hit->t_m;
    }
  }
  if (range_m < params_.min_range_m || range_m > params_.max_range_m) return reading;
  reading.range_m = range_m + noise_m;
  reading.valid = true;
  return reading;
}

std::optional<perception::RangeReading> RangeSensor::Update(const control::QuadState& state) {
  if (!schedule_.Due(state.t_s)) return std::nullopt;
  return Measure(state);
}

}  // namespace aperture::sim
