#include "perception/camera/equidistant_camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aperture::perception {

EquidistantCamera::EquidistantCamera(int width, int height, const PinholeIntrinsics& intrinsics,
                                     const EquidistantDistortion& distortion)
    : CameraModel(width, height), k_(intrinsics), d_(distortion) {
  k_.Validate(width, height);
  const char* names[] = {"k1", "k2", "k3", "k4"};
  const double values[] = {d_.k1, d_.k2, d_.k3, d_.k4};
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(values[i]))
      throw std::invalid_argument(std::string("equidistant distortion coefficient ") + names[i] +
                                  " is not finite; pass finite k1 k2 k3 k4");
  }
  // First zero of d theta_d / d theta on (0, pi]: scan in 1e-3 rad steps, refine by bisection.
  max_theta_ = M_PI;
  constexpr double kScanStep = 1e-3;
  for (double theta = kScanStep; theta < M_PI + kScanStep; theta += kScanStep) {
    double slope;
    DistortAngle(std::min(theta, M_PI), &slope);
    if (slope <= 0.0) {
      double lo = theta - kScanStep, hi = std::min(theta, M_PI);
      for (int i = 0; i < 100 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        DistortAngle(mid, &slope);
        (slope > 0.0 ? lo : hi) = mid;
      }
      max_theta_ = lo;
      break;
    }
  }
}

Eigen::VectorXd EquidistantCamera::distortion() const {
  return Eigen::Vector4d(d_.k1, d_.k2, d_.k3, d_.k4);
}

double EquidistantCamera::DistortAngle(double theta, double* dtheta_d_dtheta) const {
  const double t2 = theta * theta;
  const double poly = 1.0 + t2 * (d_.k1 + t2 * (d_.k2 + t2 * (d_.k3 + t2 * d_.k4)));
  if (dtheta_d_dtheta != nullptr) {
    *dtheta_d_dtheta =
        1.0 + t2 * (3.0 * d_.k1 + t2 * (5.0 * d_.k2 + t2 * (7.0 * d_.k3 + t2 * 9.0 * d_.k4)));
  }
  return theta * poly;
}

double EquidistantCamera::UndistortAngle(double theta_d) const {
  if (theta_d <= 0.0) return 0.0;
  if (theta_d >= DistortAngle(max_theta_)) return max_theta_;
  // theta_d(theta) is increasing on [0, max_theta_]: keep a bracket [lo, hi] around the root and
  // fall back to bisection when a Newton step leaves it (near max_theta_ the slope tends to zero).
  double lo = 0.0, hi = max_theta_;
  double theta = std::min(theta_d, max_theta_);
  for (int iteration = 0; iteration < 100; ++iteration) {
    double slope;
    const double f = DistortAngle(theta, &slope) - theta_d;
    // 1e-15 rad of theta_d is < 1e-12 px for any focal length below 1000 px.
    if (std::abs(f) <= 1e-15) break;
    (f > 0.0 ? hi : lo) = theta;
    double next = theta - f / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - theta) <= 1e-16 * std::max(1.0, theta)) {
      theta = next;
      break;
    }
    theta = next;
  }
  return theta;
}

bool EquidistantCamera::Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
                                Eigen::Matrix<double, 2, 3>* J_px_p) const {
  const double X = p_C.x(), Y = p_C.y(), Z = p_C.z();
  const double rho2 = X * X + Y * Y;
  const double rho = std::sqrt(rho2);
  const double n2 = rho2 + Z * Z;
  if (!(n2 > 0.0)) return false;
  // Near the optical axis (theta < ~1e-8) theta_d / rho equals 1 / Z to double precision and the
  // model is the pinhole model; the general formulas below would divide by rho ~ 0.
  if (Z > 0.0 && rho < 1e-8 * Z) {
    const double inv_z = 1.0 / Z;
    *px = k_.ToPixel(Eigen::Vector2d(X * inv_z, Y * inv_z));
    if (J_px_p != nullptr) {
      *J_px_p << k_.fx * inv_z, 0.0, -k_.fx * X * inv_z * inv_z,  //
          0.0, k_.fy * inv_z, -k_.fy * Y * inv_z * inv_z;
    }
    return true;
  }
  const double theta = std::atan2(rho, Z);
  if (!(theta <= max_theta_) || rho == 0.0) return false;  // rho == 0 here: straight behind
  double dtheta_d;
  const double theta_d = DistortAngle(theta, &dtheta_d);
  const double m = theta_d / rho;  // (x_d, y_d) = m (X, Y)
  *px = k_.ToPixel(Eigen::Vector2d(m * X, m * Y));
  if (J_px_p != nullptr) {
    // theta = atan2(rho, Z): d theta = (Z d rho - rho dZ) / n2, d rho = (X dX + Y dY) / rho.
    const Eigen::RowVector3d dtheta_dp(Z * X / (rho * n2), Z * Y / (rho * n2), -rho / n2);
    const Eigen::RowVector3d drho_dp(X / rho, Y / rho, 0.0);
    const Eigen::RowVector3d dm_dp = (dtheta_d * dtheta_dp - m * drho_dp) / rho;
    Eigen::Matrix<double, 2, 3> J_xyd_p;
    J_xyd_p.row(0) = X * dm_dp;
    J_xyd_p.row(1) = Y * dm_dp;
    J_xyd_p(0, 0) += m;
    J_xyd_p(1, 1) += m;
    *J_px_p = Eigen::Vector2d(k_.fx, k_.fy).asDiagonal() * J_xyd_p;
  }
  return true;
}

Eigen::Vector3d EquidistantCamera::Unproject(const Eigen::Vector2d& px) const {
  const Eigen::Vector2d xy_d = k_.FromPixel(px);
  const double theta_d = xy_d.norm();
  if (theta_d < 1e-12) return Eigen::Vector3d(xy_d.x(), xy_d.y(), 1.0).normalized();
  const double theta = UndistortAngle(theta_d);
  const double s = std::sin(theta) / theta_d;
  return Eigen::Vector3d(s * xy_d.x(), s * xy_d.y(), std::cos(theta));
}

std::unique_ptr<CameraModel> EquidistantCamera::Scaled(int new_width, int new_height) const {
  return std::make_unique<EquidistantCamera>(new_width, new_height,
                                             k_.Scaled(static_cast<double>(new_width) / width(),
                                                       static_cast<double>(new_height) / height()),
                                             d_);
}

std::unique_ptr<CameraModel> EquidistantCamera::Clone() const {
  return std::make_unique<EquidistantCamera>(*this);
}

}  // namespace aperture::perception
