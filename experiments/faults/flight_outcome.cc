#include "experiments/faults/flight_outcome.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "control/constants.h"
#include "control/require.h"

namespace aperture::experiments {
namespace {

std::string UnstableEnd(const char* what, double value, const char* unit, double t_s) {
  char line[120];
  std::snprintf(line, sizeof(line), "not stable at the end: %s %.2f %s at t = %.2f s", what, value,
                unit, t_s);
  return line;
}

}  // namespace

const char* ToString(FlightOutcomeKind kind) {
  switch (kind) {
    case FlightOutcomeKind::kSuccess:
      return "success";
    case FlightOutcomeKind::kSafeAbort:
      return "safe_abort";
    case FlightOutcomeKind::kCrash:
      return "crash";
  }
  return "crash";
}

FlightOutcome ClassifyFlight(bool mission_passed, const sim::SitlResult& result,
                             const SafeStateCriteria& criteria) {
  control::RequirePositive(criteria.window_s, "SafeStateCriteria.window_s");
  control::RequirePositive(criteria.max_speed_mps, "SafeStateCriteria.max_speed_mps");
  control::RequirePositive(criteria.max_tilt_deg, "SafeStateCriteria.max_tilt_deg");
  control::RequirePositive(criteria.max_rate_radps, "SafeStateCriteria.max_rate_radps");
  if (mission_passed) return {FlightOutcomeKind::kSuccess, ""};
  if (result.collision) return {FlightOutcomeKind::kCrash, result.reason};
  if (result.trajectory.empty() ||
      result.trajectory.back().t_s - result.trajectory.front().t_s < criteria.window_s) {
    return {FlightOutcomeKind::kCrash, "not stable at the end: the run is shorter than the " +
                                           std::to_string(criteria.window_s) + " s window"};
  }
  const double t_from_s = result.trajectory.back().t_s - criteria.window_s;
  for (auto it = result.trajectory.rbegin(); it != result.trajectory.rend() && it->t_s >= t_from_s;
       ++it) {
    const double speed = it->v_W.norm();
    if (!(speed <= criteria.max_speed_mps))
      return {FlightOutcomeKind::kCrash, UnstableEnd("speed", speed, "m/s", it->t_s)};
    const Eigen::Vector3d z_B = it->q_WB * Eigen::Vector3d::UnitZ();
    const double tilt_deg = std::acos(std::clamp(z_B.z(), -1.0, 1.0)) * control::kRadToDeg;
    if (!(tilt_deg <= criteria.max_tilt_deg)) {
      return {FlightOutcomeKind::kCrash, UnstableEnd("tilt", tilt_deg, "deg", it->t_s)};
    }
    const double rate = it->omega_B.head<2>().norm();
    if (!(rate <= criteria.max_rate_radps)) {
      return {FlightOutcomeKind::kCrash, UnstableEnd("roll/pitch rate", rate, "rad/s", it->t_s)};
    }
  }
  return {FlightOutcomeKind::kSafeAbort, ""};
}

}  // namespace aperture::experiments
