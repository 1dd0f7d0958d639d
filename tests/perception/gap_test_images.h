#pragma once
// Synthetic images of the seed-000 gap pattern (perception/gap/gap_detector.h) without the
// renderer, shared by the detector and mission tests.
#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/gap/gap_detector.h"

namespace aperture::perception {

// The pattern (white surround, black band, white band, gray opening) on a gray background, seen
// by `camera` at T_CG, rendered at 8x and area-averaged, so edges are anti-aliased like a real
// sensor's. Straight edges: meant for pinhole cameras. Throws std::invalid_argument when a corner
// does not project.
inline cv::Mat DrawGapPattern(const CameraModel& camera, const GapDetectorParams& p,
                              const Eigen::Isometry3d& T_CG) {
  constexpr int kScale = 8;
  constexpr int kShift = 4;  // fillConvexPoly fractional bits
  cv::Mat hi(camera.height() * kScale, camera.width() * kScale, CV_8UC1, cv::Scalar(90));
  const auto fill = [&](const Eigen::Vector2d& size, int value) {
    std::vector<cv::Point> poly;
    for (const Eigen::Vector2d& c : {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1),
                                     Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)}) {
      Eigen::Vector2d px;
      if (!camera.Project(T_CG * Eigen::Vector3d(0.5 * c.x() * size.x(), 0.5 * c.y() * size.y(), 0.0),
                          &px)) {
        throw std::invalid_argument("DrawGapPattern: a pattern corner is not in front of the camera");
      }
      // Pixel centre x of the image is at kScale * (x + 0.5) - 0.5 in the fine image.
      const Eigen::Vector2d fine =
          kScale * (px.array() + 0.5).matrix() - Eigen::Vector2d::Constant(0.5);
      poly.emplace_back(static_cast<int>(std::lround(fine.x() * (1 << kShift))),
                        static_cast<int>(std::lround(fine.y() * (1 << kShift))));
    }
    cv::fillConvexPoly(hi, poly, cv::Scalar(value), cv::LINE_8, kShift);
  };
  fill(p.outer_size_m + Eigen::Vector2d(0.4, 0.4), 235);
  fill(p.outer_size_m, 15);
  fill(p.inner_size_m, 235);
  fill(p.opening_size_m, 120);
  cv::Mat image;
  cv::resize(hi, image, cv::Size(camera.width(), camera.height()), 0, 0, cv::INTER_AREA);
  return image;
}

}  // namespace aperture::perception
