#include "planning/mono_nav/ego_dynamic_space.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::planning {

void EgoDynamicParams::Validate() const {
  if (!(response_time_s > 0.0) || !std::isfinite(response_time_s)) {
    throw std::invalid_argument("ego-dynamic space: response_time_s must be > 0, got " +
                                std::to_string(response_time_s));
  }
  if (!(max_deceleration_mps2 > 0.0) || !std::isfinite(max_deceleration_mps2)) {
    throw std::invalid_argument("ego-dynamic space: max_deceleration_mps2 must be > 0, got " +
                                std::to_string(max_deceleration_mps2));
  }
  if (!(depth_error_margin_m >= 0.0) || !std::isfinite(depth_error_margin_m)) {
    throw std::invalid_argument("ego-dynamic space: depth_error_margin_m must be >= 0, got " +
                                std::to_string(depth_error_margin_m));
  }
}

double EffectiveDistance(double d_obs_m, const EgoDynamicParams& params) {
  const double scale =
      params.max_deceleration_mps2 * params.response_time_s * params.response_time_s;  // a_b dt^2
  const double discriminant = 1.0 + 2.0 * d_obs_m / scale;
  if (discriminant <= 0.0) return -scale;
  return scale * (std::sqrt(discriminant) - 1.0);
}

double AllowedSpeed(double d_eff_m, const EgoDynamicParams& params) {
  return d_eff_m > 0.0 ? d_eff_m / params.response_time_s : 0.0;
}

cv::Mat EgoDynamicTransform(const cv::Mat& depth_m, const EgoDynamicParams& params) {
  if (depth_m.type() != CV_32FC1) {
    throw std::invalid_argument("ego-dynamic space: the depth map must be CV_32FC1 in metres");
  }
  params.Validate();
  cv::Mat d_eff(depth_m.size(), CV_32F);
  for (int r = 0; r < depth_m.rows; ++r) {
    for (int c = 0; c < depth_m.cols; ++c) {
      const double d_obs = depth_m.at<float>(r, c) - params.depth_error_margin_m;
      d_eff.at<float>(r, c) = float(EffectiveDistance(d_obs, params));
    }
  }
  return d_eff;
}

}  // namespace aperture::planning
