#include "experiments/faults/fault_injection.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "control/constants.h"
#include "control/require.h"
#include "sim/scene/counter_hash.h"

namespace aperture::experiments {
namespace {

constexpr double kGustDurationS = 1.0;
constexpr double kEarliestOnsetS = 1.0;  // after the first second: the missions have started

}  // namespace

double FaultSpec::LevelAt(double fraction) const {
  return std::round((low + fraction * (high - low)) * 1e9) / 1e9;
}

std::vector<double> FaultSpec::SweepLevels() const {
  std::vector<double> levels;
  for (double fraction : kSweepFractions) levels.push_back(LevelAt(fraction));
  return levels;
}

const std::vector<FaultSpec>& FaultCatalogue() {
  static const std::vector<FaultSpec> catalogue = {
      {FaultKind::kFrameDrop, "frame_drop", "", "frame drop probability", 0.0, 0.5},
      {FaultKind::kCameraLatency, "camera_latency", "s", "added camera latency [s]", 0.0, 0.1},
      {FaultKind::kImuNoise, "imu_noise", "x", "IMU noise factor", 1.0, 10.0},
      {FaultKind::kAccelBias, "accel_bias", "m/s^2", "accelerometer bias [m/s^2]", 0.0, 0.3},
      {FaultKind::kGust, "gust", "m/s", "1 s gust [m/s]", 0.0, 5.0},
      {FaultKind::kMotorLoss, "motor_loss", "", "motor 1 efficiency lost", 0.0, 0.3},
      {FaultKind::kPerceptionOutage, "perception_outage", "s", "perception outage [s]", 0.0, 0.5},
  };
  return catalogue;
}

const FaultSpec& FindFault(const std::string& name) {
  std::string known;
  for (const FaultSpec& fault : FaultCatalogue()) {
    if (fault.name == name) return fault;
    known += (known.empty() ? "" : ", ") + fault.name;
  }
  throw std::invalid_argument("unknown fault '" + name + "'; the faults are " + known);
}

FaultSetting ParseFaultSetting(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    throw std::invalid_argument("fault '" + text + "': write NAME=LEVEL, e.g. motor_loss=0.15");
  }
  FaultSetting setting;
  setting.fault = &FindFault(text.substr(0, equals));
  const std::string level_text = text.substr(equals + 1);
  char* end = nullptr;
  setting.level = std::strtod(level_text.c_str(), &end);
  const FaultSpec& fault = *setting.fault;
  if (level_text.empty() || *end != '\0' || !std::isfinite(setting.level) ||
      setting.level < fault.low || setting.level > fault.high) {
    std::ostringstream range;
    range << fault.low << " to " << fault.high;
    throw std::invalid_argument("fault '" + text + "': the level of " + fault.name +
                                " is a number from " + range.str() +
                                (fault.unit.empty() ? "" : " " + fault.unit));
  }
  return setting;
}

FaultDraw DrawFault(std::uint64_t seed) {
  FaultDraw draw;
  // Uniform on the sphere: a normalized Gaussian vector.
  Eigen::Vector3d v(sim::NormalFromHash(sim::HashCounters(seed, 1)),
                    sim::NormalFromHash(sim::HashCounters(seed, 2)),
                    sim::NormalFromHash(sim::HashCounters(seed, 3)));
  draw.direction_unit = v.norm() > 1e-12 ? Eigen::Vector3d(v.normalized())
                                         : Eigen::Vector3d(Eigen::Vector3d::UnitX());
  draw.heading_rad = 2.0 * control::kPi * sim::UniformFromHash(sim::HashCounters(seed, 4));
  draw.onset_fraction = sim::UniformFromHash(sim::HashCounters(seed, 5));
  return draw;
}

double FaultOnsetS(const FaultDraw& draw, double duration_s) {
  const double latest_s = std::max(kEarliestOnsetS, duration_s / 3.0);
  return kEarliestOnsetS + draw.onset_fraction * (latest_s - kEarliestOnsetS);
}

void InjectFault(FaultKind kind, double level, const FaultDraw& draw, sim::SitlRunnerParams* sitl) {
  const FaultSpec* spec = nullptr;
  for (const FaultSpec& fault : FaultCatalogue()) {
    if (fault.kind == kind) spec = &fault;
  }
  control::Require(
      std::isfinite(level) && level >= std::min(spec->low, spec->high) &&
          level <= std::max(spec->low, spec->high),
      "fault " + spec->name + " level", level,
      "must be in [" + std::to_string(spec->low) + ", " + std::to_string(spec->high) + "]");
  if (level == spec->low) return;
  const double onset_s = FaultOnsetS(draw, sitl->duration_s);
  switch (kind) {
    case FaultKind::kFrameDrop:
      // Independent of any drop the scenario has: a frame survives both.
      for (sim::SitlCamera& camera : sitl->cameras) {
        camera.drop_probability = 1.0 - (1.0 - camera.drop_probability) * (1.0 - level);
      }
      break;
    case FaultKind::kCameraLatency:
      for (sim::SitlCamera& camera : sitl->cameras) camera.latency_s += level;
      break;
    case FaultKind::kImuNoise:
      sitl->imu.ScaleNoise(level);
      break;
    case FaultKind::kAccelBias:
      sitl->imu.accel_bias_initial_B += level * draw.direction_unit;
      break;
    case FaultKind::kGust:
      sitl->disturbances.gusts.push_back(sim::WindGust{
          onset_s, kGustDurationS,
          level * Eigen::Vector3d(std::cos(draw.heading_rad), std::sin(draw.heading_rad), 0.0)});
      break;
    case FaultKind::kMotorLoss:
      if (!sitl->flight_controller_model) sitl->flight_controller_model = sitl->dynamics.vehicle;
      sitl->dynamics.vehicle.rotor_fitness(0) *= 1.0 - level;
      break;
    case FaultKind::kPerceptionOutage:
      for (sim::SitlCamera& camera : sitl->cameras) {
        camera.outages.push_back(sim::TimeWindow{onset_s, onset_s + level});
      }
      break;
  }
}

}  // namespace aperture::experiments
