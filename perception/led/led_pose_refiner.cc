#include "perception/led/led_pose_refiner.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "control/so3.h"

namespace aperture::perception {

double LargestStandardDeviation(const Eigen::Matrix3d& covariance) {
  const double largest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues().maxCoeff();
  return std::isnan(largest) ? largest : std::sqrt(std::max(0.0, largest));
}

bool ProjectLed(const CameraModel& camera, const Eigen::Isometry3d& T_CT,
                const Eigen::Vector3d& p_T, Eigen::Vector2d* px,
                Eigen::Matrix<double, 2, 6>* J_px_delta) {
  const Eigen::Vector3d p_rotated = T_CT.linear() * p_T;
  Eigen::Matrix<double, 2, 3> J_px_p;
  if (!camera.Project(p_rotated + T_CT.translation(), px, J_px_delta ? &J_px_p : nullptr)) {
    return false;
  }
  if (J_px_delta) {
    J_px_delta->leftCols<3>() = J_px_p;
    J_px_delta->rightCols<3>() = -J_px_p * control::Skew(p_rotated);
  }
  return true;
}

LedPoseRefinement RefineLedPose(const CameraModel& camera, const std::vector<Eigen::Vector3d>& p_T,
                                const std::vector<Eigen::Vector2d>& px,
                                const Eigen::Isometry3d& T_CT_initial,
                                const LedPoseRefinerParams& params) {
  LedPoseRefinement result;
  result.T_CT = T_CT_initial;
  if (p_T.size() < 3 || p_T.size() != px.size()) return result;
  Matrix6d H;
  control::Vector6d b;
  double squared_error = 0.0;
  // Normal equations at T_CT; false when a point is not projectable.
  auto linearize = [&](const Eigen::Isometry3d& T_CT) {
    H.setZero();
    b.setZero();
    squared_error = 0.0;
    for (std::size_t i = 0; i < p_T.size(); ++i) {
      Eigen::Vector2d projected;
      Eigen::Matrix<double, 2, 6> J;
      if (!ProjectLed(camera, T_CT, p_T[i], &projected, &J)) return false;
      const Eigen::Vector2d residual = projected - px[i];
      H += J.transpose() * J;
      b += J.transpose() * residual;
      squared_error += residual.squaredNorm();
    }
    return true;
  };
  for (result.iterations = 0; result.iterations < params.max_iterations; ++result.iterations) {
    if (!linearize(result.T_CT)) return result;
    const Eigen::LDLT<Matrix6d> ldlt(H);
    if (ldlt.info() != Eigen::Success) return result;
    const control::Vector6d delta = -ldlt.solve(b);
    if (!delta.allFinite()) return result;
    result.T_CT.translation() += delta.head<3>();
    result.T_CT.linear() = control::ExpSo3(delta.tail<3>()) * result.T_CT.linear();
    if (delta.norm() < params.step_tolerance) {
      ++result.iterations;
      break;
    }
  }
  if (!linearize(result.T_CT)) return result;
  // (C.9) with Sigma_D = sigma^2 I.
  const Eigen::FullPivLU<Matrix6d> lu(H);
  if (!lu.isInvertible()) return result;
  const double variance = params.detection_sigma_px * params.detection_sigma_px;
  result.covariance = variance * lu.inverse();
  result.rms_px = std::sqrt(squared_error / p_T.size());
  result.valid = true;
  return result;
}

}  // namespace aperture::perception
