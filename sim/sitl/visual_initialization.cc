#include "sim/sitl/visual_initialization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::sim {

void VisualInitializationParams::Validate() const {
  const std::string prefix = "VisualInitializationParams.";
  control::RequireNonNegative(max_tilt_rad, prefix + "max_tilt_rad");
  control::RequireNonNegative(min_height_m, prefix + "min_height_m");
  control::RequireNonNegative(max_flow_radps, prefix + "max_flow_radps");
  control::RequireNonNegative(min_baseline_ratio, prefix + "min_baseline_ratio");
  control::RequireNonNegative(latency_s, prefix + "latency_s");
  control::RequireNonNegative(position_noise_m, prefix + "position_noise_m");
  control::RequireNonNegative(velocity_noise_mps, prefix + "velocity_noise_mps");
  control::RequireNonNegative(scale_noise, prefix + "scale_noise");
  if (scale_noise >= 0.5) {
    throw std::invalid_argument("VisualInitializationParams.scale_noise must be < 0.5");
  }
  if (!offset_W.allFinite()) {
    throw std::invalid_argument("VisualInitializationParams.offset_W must be finite");
  }
}

VisualInitialization::VisualInitialization(const VisualInitializationParams& params,
                                           std::uint64_t seed)
    : params_(params), rng_(seed) {
  params_.Validate();
}

bool VisualInitialization::Update(const control::QuadState& truth, bool attempt,
                                  double estimated_height_m) {
  states_.push_back(truth);
  while (states_.size() > 1 && states_[1].t_s <= truth.t_s - params_.latency_s + 1e-9) {
    states_.pop_front();
  }
  if (initialized_) return false;
  const double height_m = truth.p_WB.z();
  const Eigen::Vector3d z_B_W = truth.q_WB * Eigen::Vector3d::UnitZ();
  const double tilt_rad = std::acos(std::clamp(z_B_W.z(), -1.0, 1.0));
  const Eigen::Vector3d omega_W = truth.q_WB * truth.omega_B;
  const bool tracking =
      attempt && tilt_rad <= params_.max_tilt_rad && height_m >= params_.min_height_m &&
      truth.v_W.head<2>().norm() / height_m + omega_W.head<2>().norm() <= params_.max_flow_radps;
  if (!tracking) {
    last_tracked_xy_W_.reset();
    baseline_m_ = 0.0;
    return false;
  }
  if (last_tracked_xy_W_) baseline_m_ += (truth.p_WB.head<2>() - *last_tracked_xy_W_).norm();
  last_tracked_xy_W_ = truth.p_WB.head<2>();
  if (baseline_m_ < params_.min_baseline_ratio * height_m) return false;
  initialized_ = true;
  initialized_at_s_ = truth.t_s;
  std::normal_distribution<double> unit(0.0, 1.0);
  scale_ = estimated_height_m / height_m * (1.0 + params_.scale_noise * unit(rng_));
  return true;
}

std::optional<control::QuadState> VisualInitialization::Estimate() {
  if (!initialized_ || states_.empty()) return std::nullopt;
  const control::QuadState& delayed = states_.front();
  if (delayed.t_s < initialized_at_s_ - 1e-9) return std::nullopt;
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto noise = [&](double sigma) -> Eigen::Vector3d {
    return sigma * Eigen::Vector3d(unit(rng_), unit(rng_), unit(rng_));
  };
  control::QuadState estimate = delayed;
  estimate.p_WB =
      scale_ * (R_VW_ * delayed.p_WB) + params_.offset_W + noise(params_.position_noise_m);
  estimate.v_W = scale_ * (R_VW_ * delayed.v_W) + noise(params_.velocity_noise_mps);
  estimate.q_WB = Eigen::Quaterniond(R_VW_) * delayed.q_WB;
  return estimate;
}

}  // namespace aperture::sim
