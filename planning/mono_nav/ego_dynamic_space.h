#pragma once
// Ego-Dynamic Space transform of a depth map (seed 003 Sec. III-B, after Minguez et al. [21]):
// the distance to an obstacle becomes the effective distance d_eff that the vehicle may cover at
// constant speed v during its response time dt and still stop before the obstacle with its
// maximum deceleration a_b:
//   d_obs = D_E - avg(e_ln)                       (estimated depth less the depth error margin)
//   d_obs = d_eff + d_brake,   d_eff = v dt,   d_brake = v^2 / (2 a_b)
//   => d_eff^2 / (2 dt^2 a_b) + d_eff - d_obs = 0
//   => d_eff = a_b dt^2 (sqrt(1 + 2 d_obs / (a_b dt^2)) - 1)            (EDT{d_obs})
// d_eff <= 0 means a collision is imminent. The paper subtracts the mean Table I error avg(e_ln)
// from the depth as a distance; we keep that literal form with the margin in metres as a
// parameter (its default is our model's held-out E_ln).
#include <opencv2/core/mat.hpp>

namespace aperture::planning {

struct EgoDynamicParams {
  // Δt: the update-cycle plus response time of the vehicle [s]. 0.3 s: one camera-rate replan
  // (33 ms) plus the attitude loop's response of a small quadrotor.
  double response_time_s = 0.3;
  // a_b: braking deceleration [m/s^2]; 3 m/s^2 keeps the tilt under ~17 deg.
  double max_deceleration_mps2 = 3.0;
  // avg(e_ln) used as a distance margin [m].
  double depth_error_margin_m = 0.3;

  void Validate() const;  // std::invalid_argument naming the field
};

// EDT{d_obs}: the effective distance [m] for an obstacle distance d_obs [m]. For d_obs below
// -a_b dt^2 / 2 (no real root) the result is -a_b dt^2, the most negative d_eff, still "imminent".
double EffectiveDistance(double d_obs_m, const EgoDynamicParams& params);

// The speed [m/s] that d_eff allows: v = d_eff / dt (0 for d_eff <= 0).
double AllowedSpeed(double d_eff_m, const EgoDynamicParams& params);

// d_eff for every entry of a depth map D_E (CV_32FC1 [m], e.g. MonoDepthEstimate::depth_m),
// CV_32FC1 of the same size. Throws std::invalid_argument for another type.
cv::Mat EgoDynamicTransform(const cv::Mat& depth_m, const EgoDynamicParams& params);

}  // namespace aperture::planning
