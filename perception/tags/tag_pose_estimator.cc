#include "perception/tags/tag_pose_estimator.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "control/so3.h"
#include "perception/tags/ippe_square.h"

namespace aperture::perception {

Eigen::Vector3d TagCorner(int k, double tag_size_m) {
  static constexpr double kSigns[4][2] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
  return {kSigns[k][0] * tag_size_m / 2, kSigns[k][1] * tag_size_m / 2, 0.0};
}

std::optional<TagPose> EstimateTagPose(const CameraModel& camera,
                                       const std::array<Eigen::Vector2d, 4>& corners_px,
                                       double tag_size_m, const TagPoseParams& params) {
  if (!(tag_size_m > 0.0)) {
    throw std::invalid_argument("EstimateTagPose: tag_size_m = " + std::to_string(tag_size_m) +
                                " must be > 0 (set apriltag.size_m / apriltag.sizes)");
  }
  std::vector<Eigen::Vector3d> p_T(4);
  std::vector<Eigen::Vector2d> px(corners_px.begin(), corners_px.end());
  std::array<Eigen::Vector2d, 4> normalized;
  for (int k = 0; k < 4; ++k) {
    p_T[k] = TagCorner(k, tag_size_m);
    const Eigen::Vector3d bearing = camera.Unproject(corners_px[k]);
    if (!(bearing.z() > 1e-9)) return std::nullopt;
    normalized[k] = bearing.hnormalized();
  }
  const std::optional<std::array<Eigen::Isometry3d, 2>> starts = IppeSquare(normalized, tag_size_m);
  if (!starts) return std::nullopt;
  std::vector<TagPoseCandidate> candidates;
  for (const Eigen::Isometry3d& start : *starts) {
    const LedPoseRefinement refined = RefineLedPose(camera, p_T, px, start, params.refiner);
    if (!refined.valid) continue;
    candidates.push_back({refined.T_CT, refined.covariance, refined.rms_px});
  }
  if (candidates.empty()) return std::nullopt;
  if (candidates.size() == 2 && candidates[1].rms_px < candidates[0].rms_px) {
    std::swap(candidates[0], candidates[1]);
  }
  const auto angle_deg = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return control::LogSo3(a.linear().transpose() * b.linear()).norm() * 180.0 / M_PI;
  };
  TagPose pose;
  pose.best = candidates[0];
  if (candidates.size() == 2 &&
      angle_deg(candidates[0].T_CT, candidates[1].T_CT) >= params.same_solution_deg) {
    pose.alternative = candidates[1];
  } else if (angle_deg((*starts)[0], (*starts)[1]) >= params.same_solution_deg) {
    // Near head-on the mirrored tilt is often no local minimum of the reprojection error:
    // Gauss-Newton slides from it into the best solution. IPPE's mirrored start stays the
    // alternative hypothesis (unrefined; its error and covariance at that pose) for the flip
    // resolver, which decides over time and across tags.
    const Eigen::Isometry3d& mirrored =
        angle_deg((*starts)[0], pose.best.T_CT) > angle_deg((*starts)[1], pose.best.T_CT)
            ? (*starts)[0]
            : (*starts)[1];
    LedPoseRefinerParams evaluate_only = params.refiner;
    evaluate_only.max_iterations = 0;
    const LedPoseRefinement at_start = RefineLedPose(camera, p_T, px, mirrored, evaluate_only);
    if (at_start.valid && angle_deg(mirrored, pose.best.T_CT) >= params.same_solution_deg) {
      pose.alternative = TagPoseCandidate{at_start.T_CT, at_start.covariance, at_start.rms_px};
      if (pose.alternative->rms_px < pose.best.rms_px) std::swap(pose.best, *pose.alternative);
    }
  }
  if (pose.alternative) {
    const double best_sq = pose.best.rms_px * pose.best.rms_px;
    const double alternative_sq = pose.alternative->rms_px * pose.alternative->rms_px;
    pose.ambiguity_ratio = alternative_sq > 0.0 ? best_sq / alternative_sq : 1.0;
  }
  return pose;
}

}  // namespace aperture::perception
