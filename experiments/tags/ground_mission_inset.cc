#include "experiments/tags/ground_mission_inset.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace aperture::experiments {
namespace {

constexpr double kInsetHeightFraction = 1.0 / 3.0;
constexpr int kInsetMarginPx = 6;

}  // namespace

void DrawGroundMissionInset(const planning::GroundMissionScene& scene,
                            const planning::GroundMissionTimeline& timeline,
                            const planning::GroundRobotSample& truth,
                            const GroundMissionInsetSizes& sizes, cv::Mat* bgr) {
  const Eigen::Vector2d extent_m = scene.area_max_W - scene.area_min_W;
  const int height_px = std::max(20, static_cast<int>(bgr->rows * kInsetHeightFraction));
  const double px_per_m = height_px / extent_m.y();
  const int width_px = static_cast<int>(extent_m.x() * px_per_m);
  if (width_px + 2 * kInsetMarginPx > bgr->cols || height_px + 2 * kInsetMarginPx > bgr->rows) {
    return;
  }
  const cv::Rect inset(kInsetMarginPx, bgr->rows - height_px - kInsetMarginPx, width_px, height_px);
  (*bgr)(inset).setTo(cv::Scalar(40, 40, 40));
  // y_W up in the inset.
  const auto pixel = [&](const Eigen::Vector2d& p_W) {
    const Eigen::Vector2d q = (p_W - scene.area_min_W) * px_per_m;
    return cv::Point(inset.x + static_cast<int>(q.x()),
                     inset.y + height_px - static_cast<int>(q.y()));
  };
  const auto box = [&](const planning::GroundBox& b, const cv::Scalar& colour, bool filled) {
    const Eigen::Rotation2Dd R(b.yaw_rad);
    std::vector<cv::Point> corners;
    for (const Eigen::Vector2d& c : {Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(0.5, -0.5),
                                    Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(-0.5, 0.5)}) {
      corners.push_back(pixel(b.p_W + R * b.size_m.cwiseProduct(c)));
    }
    if (filled) {
      cv::fillConvexPoly(*bgr, corners, colour, cv::LINE_AA);
    } else {
      cv::polylines(*bgr, corners, true, colour, 1, cv::LINE_AA);
    }
  };
  box({scene.goal_p_W, sizes.goal_m, 0.0}, cv::Scalar(60, 160, 60), true);
  for (const planning::GroundBox& fixed : scene.fixed_obstacles) {
    box(fixed, cv::Scalar(150, 150, 150), true);
  }
  for (size_t k = 0; k < truth.movable_p_W.size(); ++k) {
    box({truth.movable_p_W[k], sizes.movable_m, truth.movable_yaw_rad[k]}, cv::Scalar(0, 140, 255),
        true);
  }
  std::vector<cv::Point> path;
  constexpr double kPathStepS = 0.5;
  for (double t_s = 0.0; t_s < timeline.duration_s() + kPathStepS; t_s += kPathStepS) {
    path.push_back(pixel(timeline.Sample(std::min(t_s, timeline.duration_s())).robot_p_W));
  }
  cv::polylines(*bgr, path, false, cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
  box({truth.robot_p_W, sizes.robot_m, truth.robot_yaw_rad}, cv::Scalar(60, 60, 255), false);
  const Eigen::Vector2d front_W =
      truth.robot_p_W +
      0.5 * sizes.robot_m.x() *
          Eigen::Vector2d(std::cos(truth.robot_yaw_rad), std::sin(truth.robot_yaw_rad));
  cv::line(*bgr, pixel(truth.robot_p_W), pixel(front_W), cv::Scalar(60, 60, 255), 2, cv::LINE_AA);
  cv::rectangle(*bgr, inset, cv::Scalar(200, 200, 200), 1);
}

}  // namespace aperture::experiments
