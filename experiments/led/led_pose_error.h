#pragma once
// Pose-error metrics of `aperture bench led` (Faessler thesis C.4.1, Table C.1 and Fig. C.7):
// position error |p_est - p_true| [m] and orientation error = angle of the angle-axis form of
// R_est R_true^T [deg], per frame, and their statistics over a sequence. Poses are T_CT (target in
// camera); frames without an estimate count in `frames` but not in the error statistics.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace aperture::experiments {

struct PoseError {
  double position_m = 0.0;
  double orientation_deg = 0.0;
};

PoseError ComputePoseError(const Eigen::Isometry3d& T_CT_estimated,
                           const Eigen::Isometry3d& T_CT_true);

// Mean, population standard deviation and maximum; NaN without any estimate.
struct PoseErrorStatistics {
  int frames = 0;
  int frames_with_pose = 0;
  double position_error_mean = 0.0;  // m
  double position_error_std = 0.0;
  double position_error_max = 0.0;
  double orientation_error_mean_deg = 0.0;
  double orientation_error_std_deg = 0.0;
  double orientation_error_max_deg = 0.0;

  // The fields under their own names (NaN -> null).
  nlohmann::json ToJson() const;
};

// One entry per frame; std::nullopt = no pose for that frame.
PoseErrorStatistics ComputePoseErrorStatistics(const std::vector<std::optional<PoseError>>& errors);

// Hand-eye alignment as in thesis C.4.1: the motion capture measures markers M on the camera,
// not its centre of projection, so the thesis estimates T_CM from the first 10 % of the data.
// From pairs of an estimate T_CT and the motion capture's T_MT of the same frame: T_CM =
// T_CT T_MT^-1 averaged (rotations by control::MeanRotation, then t_CT - R_CM t_MT averaged).
// Throws std::invalid_argument for no pairs.
Eigen::Isometry3d EstimateHandEye(const std::vector<Eigen::Isometry3d>& T_CT_estimated,
                                  const std::vector<Eigen::Isometry3d>& T_MT_measured);

// Squared Mahalanobis distance of the estimate from the truth under the estimate's covariance
// (perception::LedPoseRefinement's parametrisation: [p_CT [m]; rotation vector in C [rad]] with
// T_CT = (Exp(delta_phi) R_CT, p_CT + delta_t)). Infinite when the covariance is not positive
// definite.
double PoseMahalanobisSquared(const Eigen::Isometry3d& T_CT_estimated,
                              const Eigen::Matrix<double, 6, 6>& covariance,
                              const Eigen::Isometry3d& T_CT_true);

// A "confident wrong pose" (issue 6 acceptance for merged LEDs): the error exceeds the accuracy
// bounds (position > max_position_m or orientation > max_orientation_deg) while the covariance
// claims it is improbable: squared Mahalanobis distance > kConfidentChiSquared (chi^2 with 6
// degrees of freedom at 99.9 %). A wrong pose with a covariance that covers it is honest.
constexpr double kConfidentChiSquared = 22.46;
bool IsConfidentWrongPose(const Eigen::Isometry3d& T_CT_estimated,
                          const Eigen::Matrix<double, 6, 6>& covariance,
                          const Eigen::Isometry3d& T_CT_true, double max_position_m = 0.02,
                          double max_orientation_deg = 2.0);

}  // namespace aperture::experiments
