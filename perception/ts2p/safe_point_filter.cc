#include "perception/ts2p/safe_point_filter.h"

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

namespace aperture::perception {

void SafePointFilterParams::Validate() const {
  if (!(acceleration_psd > 0.0) || !(measurement_sigma_px > 0.0)) {
    throw std::invalid_argument(
        "gap_tracker.filter.acceleration_psd and measurement_sigma_px must be > 0");
  }
}

SafePointFilter::SafePointFilter(const SafePointFilterParams& params) : params_(params) {
  params_.Validate();
}

void SafePointFilter::Reset(const Eigen::Vector2d& x_s_px, double t_s) {
  x_ << x_s_px, 0.0, 0.0;
  P_.setZero();
  P_.topLeftCorner<2, 2>().diagonal().setConstant(params_.measurement_sigma_px *
                                                  params_.measurement_sigma_px);
  // Unknown initial drift: ~100 px/s std.
  P_.bottomRightCorner<2, 2>().diagonal().setConstant(1.0e4);
  t_s_ = t_s;
  initialized_ = true;
}

Eigen::Vector2d SafePointFilter::Update(const Eigen::Vector2d& measured_px, double t_s) {
  if (!initialized_) {
    Reset(measured_px, t_s);
    return measured_px;
  }
  if (t_s < t_s_) {
    throw std::invalid_argument("SafePointFilter::Update: time " + std::to_string(t_s) +
                                " s is before the last update " + std::to_string(t_s_) + " s");
  }
  const double dt = t_s - t_s_;
  t_s_ = t_s;
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = F(1, 3) = dt;
  // Q of the continuous white-noise acceleration model per axis: q [dt^3/3, dt^2/2; dt^2/2, dt].
  const double q = params_.acceleration_psd;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    Q(axis, axis) = q * dt * dt * dt / 3.0;
    Q(axis, axis + 2) = Q(axis + 2, axis) = q * dt * dt / 2.0;
    Q(axis + 2, axis + 2) = q * dt;
  }
  x_ = F * x_;
  P_ = F * P_ * F.transpose() + Q;
  Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
  H(0, 0) = H(1, 1) = 1.0;
  const Eigen::Matrix2d R =
      Eigen::Matrix2d::Identity() * params_.measurement_sigma_px * params_.measurement_sigma_px;
  const Eigen::Matrix2d S = H * P_ * H.transpose() + R;
  const Eigen::Matrix<double, 4, 2> K = P_ * H.transpose() * S.inverse();
  x_ += K * (measured_px - H * x_);
  P_ = (Eigen::Matrix4d::Identity() - K * H) * P_;
  return x_.head<2>();
}

}  // namespace aperture::perception
