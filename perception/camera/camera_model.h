#pragma once
// Camera model interface. Frame C follows OpenCV: x right, y down, z forward. Pixel coordinates
// have their origin at the centre of the top-left pixel (OpenCV convention), units px.
//
// Implementations: PinholeCamera, RadTanCamera (OpenCV k1 k2 p1 p2 [k3]), EquidistantCamera
// (OpenCV fisheye k1..k4, valid beyond 90 deg off axis so a 180 deg lens is representable).
#include <Eigen/Core>
#include <memory>
#include <string>

namespace aperture::perception {

class CameraModel {
 public:
  virtual ~CameraModel() = default;

  int width() const { return width_; }
  int height() const { return height_; }
  // "pinhole", "radtan" or "equidistant".
  virtual std::string model_name() const = 0;

  // Projects a point p_C [m] in the camera frame to a pixel. Returns false (and leaves the
  // outputs untouched) when the point is not projectable by the model (behind a pinhole camera,
  // beyond the fisheye's valid angle, at the optical centre). Does not check the image bounds.
  // J_px_p (optional) receives d(pixel)/d(p_C), 2x3.
  virtual bool Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
                       Eigen::Matrix<double, 2, 3>* J_px_p = nullptr) const = 0;

  // Unit bearing vector in C of the ray through pixel px. Always defined for pixels in the image.
  virtual Eigen::Vector3d Unproject(const Eigen::Vector2d& px) const = 0;

  // True when px lies inside the image with at least border_px to every edge.
  bool IsInImage(const Eigen::Vector2d& px, double border_px = 0.0) const {
    return px.x() >= -0.5 + border_px && px.y() >= -0.5 + border_px &&
           px.x() <= width_ - 0.5 - border_px && px.y() <= height_ - 0.5 - border_px;
  }

  // The same lens on a sensor resampled to new_width x new_height (focal lengths and principal
  // point scaled, distortion unchanged).
  virtual std::unique_ptr<CameraModel> Scaled(int new_width, int new_height) const = 0;
  virtual std::unique_ptr<CameraModel> Clone() const = 0;

  // Linear projection parameters [fx, fy, cx, cy] in px (same meaning for every model).
  virtual Eigen::Vector4d intrinsics() const = 0;
  // Distortion coefficients in OpenCV order: empty (pinhole), k1 k2 p1 p2 [k3] (radtan),
  // k1 k2 k3 k4 (equidistant).
  virtual Eigen::VectorXd distortion() const = 0;

 protected:
  CameraModel(int width, int height) : width_(width), height_(height) {}

 private:
  int width_;
  int height_;
};

}  // namespace aperture::perception
