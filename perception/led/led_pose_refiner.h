#pragma once
// Pose refinement of the LED target (Faessler thesis (C.8), (C.9)): Gauss-Newton on SE(3)
// minimising the reprojection error of LEDs p_T against their detections px, starting from a P3P
// solution, and the pose covariance Sigma_P = (J^T Sigma_D^-1 J)^-1 as its by-product.
//
// Perturbation (also the covariance's parametrisation, PoseEstimate order [translation;
// rotation]): T_CT(delta) = (Exp(delta_phi) R_CT, p_CT + delta_t), delta = [delta_t; delta_phi],
// delta_phi a rotation vector in C. Then d p_C / d delta = [I, -(R_CT p_T)^], and the 2x6 Jacobian
// is the camera model's 2x3 projection Jacobian times it, in closed form for any camera model.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct LedPoseRefinerParams {
  int max_iterations = 10;      // Gauss-Newton converges in 2-4 steps from a P3P start
  double step_tolerance = 1e-9;  // stop when |delta| (m, rad) falls below
  double detection_sigma_px = 1.0;  // Sigma_D = sigma^2 I; thesis: conservatively 1 px^2
};

struct LedPoseRefinement {
  bool valid = false;  // false: an LED left the model's domain or the normal equations are singular
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Zero();  // [p_CT [m]; rotation [rad]], (C.9)
  double rms_px = 0.0;                     // RMS reprojection error at T_CT
  int iterations = 0;
};

// Square root of the largest eigenvalue of a 3x3 covariance block (e.g. the position or the
// rotation block of LedPoseRefinement::covariance): the standard deviation along its worst
// direction [m or rad]. NaN stays NaN; negative round-off counts as 0.
double LargestStandardDeviation(const Eigen::Matrix3d& covariance);

// Projection of p_T at T_CT and its 2x6 Jacobian w.r.t. the perturbation above. False when the
// camera cannot project the point.
bool ProjectLed(const CameraModel& camera, const Eigen::Isometry3d& T_CT,
                const Eigen::Vector3d& p_T, Eigen::Vector2d* px,
                Eigen::Matrix<double, 2, 6>* J_px_delta = nullptr);

// Refines T_CT_initial on pairs (p_T[i], px[i]); needs >= 3 pairs (else invalid).
LedPoseRefinement RefineLedPose(const CameraModel& camera, const std::vector<Eigen::Vector3d>& p_T,
                                const std::vector<Eigen::Vector2d>& px,
                                const Eigen::Isometry3d& T_CT_initial,
                                const LedPoseRefinerParams& params = {});

}  // namespace aperture::perception
