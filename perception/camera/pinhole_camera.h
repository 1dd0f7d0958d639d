#pragma once
// Pinhole camera without distortion, and the linear intrinsics shared by every model.
// Pixel = K * (x/z, y/z, 1) with K = [fx 0 cx; 0 fy cy; 0 0 1] (OpenCV convention, pixel centre
// of the top-left pixel at (0, 0)). Points with z <= 0 are not projectable.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

// Linear part of every camera model: normalized image-plane coordinates (x, y) <-> pixels.
struct PinholeIntrinsics {
  double fx = 1.0;  // focal length along x [px]
  double fy = 1.0;  // focal length along y [px]
  double cx = 0.0;  // principal point x [px]
  double cy = 0.0;  // principal point y [px]

  static PinholeIntrinsics FromVector(const Eigen::Vector4d& fx_fy_cx_cy);
  Eigen::Vector4d AsVector() const { return {fx, fy, cx, cy}; }

  // Throws std::invalid_argument naming the field when the image size is not positive, fx or fy
  // is not a positive finite number or cx, cy are not finite.
  void Validate(int width, int height) const;

  // Intrinsics of the image resampled by factors sx, sy (new size / old size), keeping pixel
  // centres aligned: c' = (c + 0.5) * s - 0.5, f' = f * s.
  PinholeIntrinsics Scaled(double sx, double sy) const;

  Eigen::Vector2d ToPixel(const Eigen::Vector2d& xy) const {
    return {fx * xy.x() + cx, fy * xy.y() + cy};
  }
  Eigen::Vector2d FromPixel(const Eigen::Vector2d& px) const {
    return {(px.x() - cx) / fx, (px.y() - cy) / fy};
  }
};

class PinholeCamera final : public CameraModel {
 public:
  // Throws std::invalid_argument on an invalid size or intrinsics (see PinholeIntrinsics).
  PinholeCamera(int width, int height, const PinholeIntrinsics& intrinsics);

  std::string model_name() const override { return "pinhole"; }
  bool Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
               Eigen::Matrix<double, 2, 3>* J_px_p = nullptr) const override;
  Eigen::Vector3d Unproject(const Eigen::Vector2d& px) const override;
  std::unique_ptr<CameraModel> Scaled(int new_width, int new_height) const override;
  std::unique_ptr<CameraModel> Clone() const override;
  Eigen::Vector4d intrinsics() const override { return k_.AsVector(); }
  Eigen::VectorXd distortion() const override { return Eigen::VectorXd(); }

 private:
  PinholeIntrinsics k_;
};

}  // namespace aperture::perception
