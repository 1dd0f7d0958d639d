#pragma once
// Equidistant fisheye camera, OpenCV's cv::fisheye model (Kannala-Brandt with 4 coefficients):
//   theta = atan2(|(X, Y)|, Z)  (angle off the optical axis, up to and beyond 90 deg)
//   theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)
//   (x_d, y_d) = theta_d * (X, Y) / |(X, Y)|,  pixel = (fx x_d + cx, fy y_d + cy)
// For theta < 90 deg this equals OpenCV's formulation with r = |(X/Z, Y/Z)|, theta = atan(r).
// Validity: the model is valid while theta_d(theta) is increasing; max_valid_angle() is the first
// zero of d theta_d / d theta in (0, pi], or pi (computed at construction). A 180 deg lens has
// max_valid_angle() >= pi/2 and projects points with Z <= 0. Points beyond the valid angle, and the
// point straight behind the camera (theta = pi), are not projectable.
// Unproject solves theta_d(theta) = |(x_d, y_d)| with safeguarded Newton on [0, max angle];
// pixels beyond the valid image circle map to rays at the valid angle.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "perception/camera/camera_model.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::perception {

struct EquidistantDistortion {
  double k1 = 0.0;
  double k2 = 0.0;
  double k3 = 0.0;
  double k4 = 0.0;
};

class EquidistantCamera final : public CameraModel {
 public:
  // Throws std::invalid_argument on an invalid size, intrinsics or a non-finite coefficient.
  EquidistantCamera(int width, int height, const PinholeIntrinsics& intrinsics,
                    const EquidistantDistortion& distortion);

  std::string model_name() const override { return "equidistant"; }
  bool Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
               Eigen::Matrix<double, 2, 3>* J_px_p = nullptr) const override;
  Eigen::Vector3d Unproject(const Eigen::Vector2d& px) const override;
  std::unique_ptr<CameraModel> Scaled(int new_width, int new_height) const override;
  std::unique_ptr<CameraModel> Clone() const override;
  Eigen::Vector4d intrinsics() const override { return k_.AsVector(); }
  Eigen::VectorXd distortion() const override;

  // Largest valid angle off the optical axis [rad], in (0, pi].
  double max_valid_angle() const { return max_theta_; }

  // theta_d(theta) and its derivative d theta_d / d theta.
  double DistortAngle(double theta, double* dtheta_d_dtheta = nullptr) const;
  // Inverse of DistortAngle on [0, max_valid_angle()], clamped to that interval.
  double UndistortAngle(double theta_d) const;

 private:
  PinholeIntrinsics k_;
  EquidistantDistortion d_;
  double max_theta_;
};

}  // namespace aperture::perception
