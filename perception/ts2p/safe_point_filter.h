#pragma once
// SafePointFilter: a Kalman filter smoothing the safe point x_s of the label tracker (seed 002
// Sec. III-A: "due to resetting and active switching, x_s can jump around ... a simple Kalman
// filter with a forward motion model is used to smooth out the value of x_s"). State
// [u, v, du/dt, dv/dt] [px, px/s] with a constant-velocity (forward) model: during the approach
// x_s drifts smoothly as the opening expands about the FOE. White-acceleration process noise
// (Bar-Shalom, discretized continuous white noise acceleration) and isotropic pixel measurement
// noise.
#include <Eigen/Core>

namespace aperture::perception {

struct SafePointFilterParams {
  // Acceleration spectral density [px^2/s^3]: the velocity of x_s may wander by ~20 px/s per
  // sqrt(s) (x_s 100 px off the FOE at 1.5 %/frame divergence moves at ~45 px/s and changes
  // that over the ~1 s approach).
  double acceleration_psd = 400.0;
  // Measurement std [px]: a median switch between F and B moves x_s by a few px.
  double measurement_sigma_px = 4.0;
  void Validate() const;
};

class SafePointFilter {
 public:
  explicit SafePointFilter(const SafePointFilterParams& params);

  void Reset(const Eigen::Vector2d& x_s_px, double t_s);
  // Predicts to t_s (>= the last time) and fuses the measurement; returns the filtered x_s.
  Eigen::Vector2d Update(const Eigen::Vector2d& measured_px, double t_s);

  bool initialized() const { return initialized_; }
  Eigen::Vector2d position_px() const { return x_.head<2>(); }
  Eigen::Vector2d velocity_px_per_s() const { return x_.tail<2>(); }

 private:
  SafePointFilterParams params_;
  bool initialized_ = false;
  double t_s_ = 0.0;
  Eigen::Vector4d x_ = Eigen::Vector4d::Zero();
  Eigen::Matrix4d P_ = Eigen::Matrix4d::Identity();
};

}  // namespace aperture::perception
