#include "perception/camera/pinhole_camera.h"

#include <cmath>
#include <stdexcept>

namespace aperture::perception {

PinholeIntrinsics PinholeIntrinsics::FromVector(const Eigen::Vector4d& fx_fy_cx_cy) {
  return {fx_fy_cx_cy[0], fx_fy_cx_cy[1], fx_fy_cx_cy[2], fx_fy_cx_cy[3]};
}

void PinholeIntrinsics::Validate(int width, int height) const {
  auto fail = [](const std::string& field, const std::string& value, const std::string& rule) {
    throw std::invalid_argument("camera " + field + " = " + value + " is invalid: " + rule);
  };
  if (width <= 0) fail("width", std::to_string(width), "the image width must be > 0 px");
  if (height <= 0) fail("height", std::to_string(height), "the image height must be > 0 px");
  if (!(std::isfinite(fx) && fx > 0.0))
    fail("fx", std::to_string(fx), "the focal length must be a finite number > 0 px");
  if (!(std::isfinite(fy) && fy > 0.0))
    fail("fy", std::to_string(fy), "the focal length must be a finite number > 0 px");
  if (!std::isfinite(cx)) fail("cx", std::to_string(cx), "the principal point must be finite");
  if (!std::isfinite(cy)) fail("cy", std::to_string(cy), "the principal point must be finite");
}

PinholeIntrinsics PinholeIntrinsics::Scaled(double sx, double sy) const {
  return {fx * sx, fy * sy, (cx + 0.5) * sx - 0.5, (cy + 0.5) * sy - 0.5};
}

PinholeCamera::PinholeCamera(int width, int height, const PinholeIntrinsics& intrinsics)
    : CameraModel(width, height), k_(intrinsics) {
  k_.Validate(width, height);
}

bool PinholeCamera::Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
                            Eigen::Matrix<double, 2, 3>* J_px_p) const {
  const double z = p_C.z();
  if (!(z > 0.0)) return false;
  const double inv_z = 1.0 / z;
  const Eigen::Vector2d xy(p_C.x() * inv_z, p_C.y() * inv_z);
  *px = k_.ToPixel(xy);
  if (J_px_p != nullptr) {
    *J_px_p << k_.fx * inv_z, 0.0, -k_.fx * xy.x() * inv_z,  //
        0.0, k_.fy * inv_z, -k_.fy * xy.y() * inv_z;
  }
  return true;
}

Eigen::Vector3d PinholeCamera::Unproject(const Eigen::Vector2d& px) const {
  const Eigen::Vector2d xy = k_.FromPixel(px);
  return Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
}

std::unique_ptr<CameraModel> PinholeCamera::Scaled(int new_width, int new_height) const {
  return std::make_unique<PinholeCamera>(new_width, new_height,
                                         k_.Scaled(static_cast<double>(new_width) / width(),
                                                   static_cast<double>(new_height) / height()));
}

std::unique_ptr<CameraModel> PinholeCamera::Clone() const {
  return std::make_unique<PinholeCamera>(*this);
}

}  // namespace aperture::perception
