#include "experiments/led/led_pose_error.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "control/constants.h"
#include "control/so3.h"
#include "experiments/bench/sample_statistics.h"

namespace aperture::experiments {
namespace {

using control::kRadToDeg;

}  // namespace

PoseError ComputePoseError(const Eigen::Isometry3d& T_CT_estimated,
                           const Eigen::Isometry3d& T_CT_true) {
  PoseError error;
  error.position_m = (T_CT_estimated.translation() - T_CT_true.translation()).norm();
  const Eigen::AngleAxisd rotation(T_CT_estimated.linear() * T_CT_true.linear().transpose());
  error.orientation_deg = std::abs(rotation.angle()) * kRadToDeg;
  return error;
}

PoseErrorStatistics ComputePoseErrorStatistics(
    const std::vector<std::optional<PoseError>>& errors) {
  PoseErrorStatistics stats;
  stats.frames = static_cast<int>(errors.size());
  double sum_p = 0.0, sum_p2 = 0.0, sum_o = 0.0, sum_o2 = 0.0;
  for (const std::optional<PoseError>& error : errors) {
    if (!error) continue;
    ++stats.frames_with_pose;
    sum_p += error->position_m;
    sum_p2 += error->position_m * error->position_m;
    sum_o += error->orientation_deg;
    sum_o2 += error->orientation_deg * error->orientation_deg;
    stats.position_error_max = std::max(stats.position_error_max, error->position_m);
    stats.orientation_error_max_deg =
        std::max(stats.orientation_error_max_deg, error->orientation_deg);
  }
  const double n = stats.frames_with_pose;
  if (n == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    stats.position_error_mean = stats.position_error_std = stats.position_error_max = nan;
    stats.orientation_error_mean_deg = stats.orientation_error_std_deg = nan;
    stats.orientation_error_max_deg = nan;
    return stats;
  }
  stats.position_error_mean = sum_p / n;
  stats.orientation_error_mean_deg = sum_o / n;
  // Population variance; clamped against round-off for identical errors.
  stats.position_error_std =
      std::sqrt(std::max(0.0, sum_p2 / n - stats.position_error_mean * stats.position_error_mean));
  stats.orientation_error_std_deg = std::sqrt(std::max(
      0.0, sum_o2 / n - stats.orientation_error_mean_deg * stats.orientation_error_mean_deg));
  return stats;
}

nlohmann::json PoseErrorStatistics::ToJson() const {
  return {{"frames", frames},
          {"frames_with_pose", frames_with_pose},
          {"position_error_mean", FiniteOrNull(position_error_mean)},
          {"position_error_std", FiniteOrNull(position_error_std)},
          {"position_error_max", FiniteOrNull(position_error_max)},
          {"orientation_error_mean_deg", FiniteOrNull(orientation_error_mean_deg)},
          {"orientation_error_std_deg", FiniteOrNull(orientation_error_std_deg)},
          {"orientation_error_max_deg", FiniteOrNull(orientation_error_max_deg)}};
}

double PoseMahalanobisSquared(const Eigen::Isometry3d& T_CT_estimated,
                              const Eigen::Matrix<double, 6, 6>& covariance,
                              const Eigen::Isometry3d& T_CT_true) {
  // The perturbation that maps the truth onto the estimate, in the covariance's parametrisation.
  Eigen::Matrix<double, 6, 1> delta;
  delta.head<3>() = T_CT_estimated.translation() - T_CT_true.translation();
  const Eigen::AngleAxisd rotation(T_CT_estimated.linear() * T_CT_true.linear().transpose());
  delta.tail<3>() = rotation.angle() * rotation.axis();
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(covariance);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  return delta.dot(ldlt.solve(delta));
}

bool IsConfidentWrongPose(const Eigen::Isometry3d& T_CT_estimated,
                          const Eigen::Matrix<double, 6, 6>& covariance,
                          const Eigen::Isometry3d& T_CT_true, double max_position_m,
                          double max_orientation_deg) {
  const PoseError error = ComputePoseError(T_CT_estimated, T_CT_true);
  if (error.position_m <= max_position_m && error.orientation_deg <= max_orientation_deg) {
    return false;
  }
  return PoseMahalanobisSquared(T_CT_estimated, covariance, T_CT_true) > kConfidentChiSquared;
}

Eigen::Isometry3d EstimateHandEye(const std::vector<Eigen::Isometry3d>& T_CT_estimated,
                                  const std::vector<Eigen::Isometry3d>& T_MT_measured) {
  if (T_CT_estimated.empty() || T_CT_estimated.size() != T_MT_measured.size()) {
    throw std::invalid_argument("EstimateHandEye: needs pairs of estimated and measured poses");
  }
  std::vector<Eigen::Quaterniond> rotations;
  for (size_t k = 0; k < T_CT_estimated.size(); ++k) {
    rotations.emplace_back(T_CT_estimated[k].linear() * T_MT_measured[k].linear().transpose());
  }
  Eigen::Isometry3d T_CM = Eigen::Isometry3d::Identity();
  T_CM.linear() = control::MeanRotation(rotations).toRotationMatrix();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < T_CT_estimated.size(); ++k) {
    sum += T_CT_estimated[k].translation() - T_CM.linear() * T_MT_measured[k].translation();
  }
  T_CM.translation() = sum / static_cast<double>(T_CT_estimated.size());
  return T_CM;
}

}  // namespace aperture::experiments
