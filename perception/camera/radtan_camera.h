#pragma once
// Radial-tangential ("plumb bob") camera, OpenCV's default distortion model:
//   (x, y) = (X/Z, Y/Z), r^2 = x^2 + y^2, radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//   x_d = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y_d = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//   pixel = (fx x_d + cx, fy y_d + cy)
// Points with Z <= 0 are not projectable. The polynomial folds back for strong negative k1; the
// model is treated as valid while the radial map r -> r * radial(r) is increasing, i.e. for
// r < max_valid_radius() (computed at construction, +infinity when it never folds). Projection of
// points beyond it returns false, so no point outside the field of view folds into the image.
// Unproject inverts the distortion with Gauss-Newton (2-D Newton with backtracking) to a
// residual below 1e-11 px for pixels inside the valid radius.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "perception/camera/camera_model.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::perception {

struct RadTanDistortion {
  double k1 = 0.0;
  double k2 = 0.0;
  double p1 = 0.0;
  double p2 = 0.0;
  double k3 = 0.0;
  // 4 or 5 coefficients (k1 k2 p1 p2 [k3]); a 4-coefficient model is saved with 4 coefficients.
  bool has_k3 = false;
};

class RadTanCamera final : public CameraModel {
 public:
  // Throws std::invalid_argument on an invalid size, intrinsics or a non-finite coefficient.
  RadTanCamera(int width, int height, const PinholeIntrinsics& intrinsics,
               const RadTanDistortion& distortion);

  std::string model_name() const override { return "radtan"; }
  bool Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
               Eigen::Matrix<double, 2, 3>* J_px_p = nullptr) const override;
  Eigen::Vector3d Unproject(const Eigen::Vector2d& px) const override;
  std::unique_ptr<CameraModel> Scaled(int new_width, int new_height) const override;
  std::unique_ptr<CameraModel> Clone() const override;
  Eigen::Vector4d intrinsics() const override { return k_.AsVector(); }
  Eigen::VectorXd distortion() const override;

  // Largest undistorted normalized radius r = |(X/Z, Y/Z)| for which the model is valid.
  double max_valid_radius() const { return max_radius_; }

  // Distorted normalized coordinates of undistorted (x, y), with optional 2x2 Jacobian.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* J = nullptr) const;

 private:
  PinholeIntrinsics k_;
  RadTanDistortion d_;
  double max_radius_;
};

}  // namespace aperture::perception
