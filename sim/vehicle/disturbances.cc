#include "sim/vehicle/disturbances.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::sim {
namespace {

// Events closer than this to a segment boundary are treated as on it [s]; far below any
// integration step, far above the rounding of accumulated simulator time.
constexpr double kTimeEpsilon_s = 1e-9;

}  // namespace

void DisturbanceParams::Validate() const {
  control::RequireFinite(steady_wind_W_mps, "DisturbanceParams.steady_wind_W_mps");
  control::RequireFinite(torque_B_Nm, "DisturbanceParams.torque_B_Nm");
  for (size_t i = 0; i < gusts.size(); ++i) {
    const std::string name = "DisturbanceParams.gusts[" + std::to_string(i) + "]";
    control::RequireFinite(gusts[i].t_start_s, name + ".t_start_s");
    control::RequireFinite(gusts[i].wind_W_mps, name + ".wind_W_mps");
    control::RequirePositive(gusts[i].duration_s, name + ".duration_s");
  }
  for (size_t i = 0; i < pushes.size(); ++i) {
    const Push& push = pushes[i];
    control::Require(std::isfinite(push.t_s) && push.impulse_W_Ns.allFinite() &&
                         push.angular_impulse_B_Nms.allFinite(),
                     "DisturbanceParams.pushes[" + std::to_string(i) + "]", "must be finite");
  }
}

Disturbances::Disturbances(const DisturbanceParams& params) : params_(params) {
  params_.Validate();
  std::stable_sort(params_.pushes.begin(), params_.pushes.end(),
                   [](const Push& a, const Push& b) { return a.t_s < b.t_s; });
  for (const WindGust& gust : params_.gusts) {
    event_times_s_.push_back(gust.t_start_s);
    event_times_s_.push_back(gust.t_start_s + gust.duration_s);
  }
  for (const Push& push : params_.pushes) event_times_s_.push_back(push.t_s);
  std::sort(event_times_s_.begin(), event_times_s_.end());
}

Eigen::Vector3d Disturbances::WindVelocity_W(double t_s) const {
  Eigen::Vector3d wind_W = params_.steady_wind_W_mps;
  for (const WindGust& gust : params_.gusts) {
    if (t_s >= gust.t_start_s && t_s < gust.t_start_s + gust.duration_s) wind_W += gust.wind_W_mps;
  }
  return wind_W;
}

void Disturbances::StepVehicle(double dt_s, QuadrotorDynamics* vehicle) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
    throw std::invalid_argument("Disturbances::StepVehicle: dt_s must be finite and > 0, got " +
                                std::to_string(dt_s));
  }
  double t_s = vehicle->state().t_s;
  const double t_end_s = t_s + dt_s;
  vehicle->SetExternalTorque_B(params_.torque_B_Nm);
  while (t_end_s - t_s > kTimeEpsilon_s) {
    while (next_push_ < static_cast<int>(params_.pushes.size()) &&
           params_.pushes[next_push_].t_s <= t_s + kTimeEpsilon_s) {
      const Push& push = params_.pushes[next_push_++];
      vehicle->ApplyImpulse(push.impulse_W_Ns, push.angular_impulse_B_Nms);
    }
    const auto next_event = std::upper_bound(event_times_s_.begin(), event_times_s_.end(),
                                             t_s + kTimeEpsilon_s);
    const double segment_end_s =
        next_event == event_times_s_.end() ? t_end_s : std::min(*next_event, t_end_s);
    // The wind is constant between events; sample it mid-segment, away from the edges.
    vehicle->SetWindVelocity_W(WindVelocity_W(0.5 * (t_s + segment_end_s)));
    vehicle->Step(segment_end_s - t_s);
    t_s = segment_end_s;
  }
}

}  // namespace aperture::sim
