#include "control/launch_detector.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::control {

LaunchDetectorParams LaunchDetectorParams::FromVehicle(const VehicleParameters& vehicle) {
  vehicle.Validate();
  LaunchDetectorParams params;
  params.idle_thrust_mps2 = vehicle.rotor_fitness.sum() * vehicle.rotor.MinThrust() /
                            vehicle.mass_kg;
  return params;
}

void LaunchDetectorParams::Validate() const {
  if (!(window_s > 0.0) || !std::isfinite(window_s)) {
    throw std::invalid_argument("LaunchDetectorParams::window_s = " + std::to_string(window_s) +
                                " must be finite and > 0");
  }
  if (!(threshold_mps2 >= 0.0) || !std::isfinite(threshold_mps2)) {
    throw std::invalid_argument("LaunchDetectorParams::threshold_mps2 = " +
                                std::to_string(threshold_mps2) + " must be finite and >= 0");
  }
  if (!(idle_thrust_mps2 >= 0.0) || !std::isfinite(idle_thrust_mps2)) {
    throw std::invalid_argument("LaunchDetectorParams::idle_thrust_mps2 = " +
                                std::to_string(idle_thrust_mps2) + " must be finite and >= 0");
  }
}

LaunchDetector::LaunchDetector(const LaunchDetectorParams& params) : params_(params) {
  params_.Validate();
}

void LaunchDetector::Reset() {
  window_.clear();
  sum_norm_ = 0.0;
  launched_ = false;
  launch_time_s_ = 0.0;
}

double LaunchDetector::MeanAccelNorm() const {
  return window_.empty() ? 0.0 : sum_norm_ / static_cast<double>(window_.size());
}

bool LaunchDetector::AddSample(double t_s, const Eigen::Vector3d& specific_force_B) {
  if (!std::isfinite(t_s) || (!window_.empty() && !(t_s > window_.back().t_s))) {
    throw std::invalid_argument("LaunchDetector::AddSample: t_s = " + std::to_string(t_s) +
                                " must be finite and after the previous sample");
  }
  if (!specific_force_B.allFinite()) {
    throw std::invalid_argument("LaunchDetector::AddSample: non-finite specific force at t_s = " +
                                std::to_string(t_s));
  }
  if (launched_) return true;
  if (window_.empty()) first_t_s_ = t_s;  // the window only empties on Reset()
  const double norm = specific_force_B.norm();
  window_.push_back({t_s, norm});
  sum_norm_ += norm;
  while (window_.front().t_s <= t_s - params_.window_s) {
    sum_norm_ -= window_.front().norm_mps2;
    window_.pop_front();
  }
  // The window is full once samples older than window_s have been seen (and dropped).
  const bool window_full = t_s - first_t_s_ >= params_.window_s;
  if (window_full && MeanAccelNorm() < params_.idle_thrust_mps2 + params_.threshold_mps2) {  // (B.29)
    launched_ = true;
    launch_time_s_ = t_s;
  }
  return launched_;
}

}  // namespace aperture::control
