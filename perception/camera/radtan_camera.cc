#include "perception/camera/radtan_camera.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace aperture::perception {
namespace {

// Smallest s = r^2 > 0 where d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)] = 1 + 3 k1 s + 5 k2 s^2 +
// 7 k3 s^3 reaches zero, searched up to r = 1e3 (an 89.9 deg half angle): the radial map folds
// there. Returns +infinity when it stays positive.
double FirstFoldRadius(const RadTanDistortion& d) {
  auto slope = [&d](double s) {
    return 1.0 + s * (3.0 * d.k1 + s * (5.0 * d.k2 + s * 7.0 * d.k3));
  };
  // Geometric scan in s from 1e-4 to 1e6, then bisection on the first sign change.
  double s_lo = 0.0;
  for (double s = 1e-4; s <= 1e6; s *= 1.01) {
    if (slope(s) <= 0.0) {
      double lo = s_lo, hi = s;
      for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (slope(mid) > 0.0 ? lo : hi) = mid;
      }
      return std::sqrt(lo);
    }
    s_lo = s;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

RadTanCamera::RadTanCamera(int width, int height, const PinholeIntrinsics& intrinsics,
                           const RadTanDistortion& distortion)
    : CameraModel(width, height), k_(intrinsics), d_(distortion) {
  k_.Validate(width, height);
  const char* names[] = {"k1", "k2", "p1", "p2", "k3"};
  const double values[] = {d_.k1, d_.k2, d_.p1, d_.p2, d_.k3};
  for (int i = 0; i < 5; ++i) {
    if (!std::isfinite(values[i]))
      throw std::invalid_argument(std::string("radtan distortion coefficient ") + names[i] +
                                  " is not finite; pass finite k1 k2 p1 p2 [k3]");
  }
  if (!d_.has_k3 && d_.k3 != 0.0)
    throw std::invalid_argument("radtan distortion: k3 is set but has_k3 is false");
  max_radius_ = FirstFoldRadius(d_);
}

Eigen::VectorXd RadTanCamera::distortion() const {
  Eigen::VectorXd c(d_.has_k3 ? 5 : 4);
  c.head<4>() << d_.k1, d_.k2, d_.p1, d_.p2;
  if (d_.has_k3) c[4] = d_.k3;
  return c;
}

Eigen::Vector2d RadTanCamera::Distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* J) const {
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d_.k1 + r2 * (d_.k2 + r2 * d_.k3));
  const Eigen::Vector2d xy_d(x * radial + 2.0 * d_.p1 * x * y + d_.p2 * (r2 + 2.0 * x * x),
                             y * radial + d_.p1 * (r2 + 2.0 * y * y) + 2.0 * d_.p2 * x * y);
  if (J != nullptr) {
    // d radial / d(r^2), then chain d(r^2)/dx = 2x.
    const double dradial_dr2 = d_.k1 + r2 * (2.0 * d_.k2 + r2 * 3.0 * d_.k3);
    const double dradial_dx = 2.0 * x * dradial_dr2;
    const double dradial_dy = 2.0 * y * dradial_dr2;
    (*J)(0, 0) = radial + x * dradial_dx + 2.0 * d_.p1 * y + 6.0 * d_.p2 * x;
    (*J)(0, 1) = x * dradial_dy + 2.0 * d_.p1 * x + 2.0 * d_.p2 * y;
    (*J)(1, 0) = y * dradial_dx + 2.0 * d_.p1 * x + 2.0 * d_.p2 * y;
    (*J)(1, 1) = radial + y * dradial_dy + 6.0 * d_.p1 * y + 2.0 * d_.p2 * x;
  }
  return xy_d;
}

bool RadTanCamera::Project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
                           Eigen::Matrix<double, 2, 3>* J_px_p) const {
  const double z = p_C.z();
  if (!(z > 0.0)) return false;
  const double inv_z = 1.0 / z;
  const Eigen::Vector2d xy(p_C.x() * inv_z, p_C.y() * inv_z);
  if (!(xy.norm() < max_radius_)) return false;
  Eigen::Matrix2d J_d_xy;
  const Eigen::Vector2d xy_d = Distort(xy, J_px_p != nullptr ? &J_d_xy : nullptr);
  *px = k_.ToPixel(xy_d);
  if (J_px_p != nullptr) {
    Eigen::Matrix<double, 2, 3> J_xy_p;
    J_xy_p << inv_z, 0.0, -xy.x() * inv_z,  //
        0.0, inv_z, -xy.y() * inv_z;
    *J_px_p = Eigen::Vector2d(k_.fx, k_.fy).asDiagonal() * J_d_xy * J_xy_p;
  }
  return true;
}

Eigen::Vector3d RadTanCamera::Unproject(const Eigen::Vector2d& px) const {
  const Eigen::Vector2d xy_d = k_.FromPixel(px);
  // Gauss-Newton on Distort(xy) = xy_d from xy = xy_d, halving steps that do not reduce the
  // residual (strong distortion can make the full Newton step overshoot near the image corners).
  Eigen::Vector2d xy = xy_d;
  Eigen::Matrix2d J;
  Eigen::Vector2d residual = Distort(xy, &J) - xy_d;
  double residual_norm = residual.norm();
  // 1e-11 px: two orders below the 1e-9 px the callers rely on.
  const double tolerance = 1e-11 / std::max(k_.fx, k_.fy);
  for (int iteration = 0; iteration < 50 && residual_norm > tolerance; ++iteration) {
    const Eigen::Vector2d step = J.inverse() * residual;  // closed-form 2x2 inverse
    bool improved = false;
    double scale = 1.0;
    for (int halving = 0; halving < 20 && !improved; ++halving, scale *= 0.5) {
      const Eigen::Vector2d candidate = xy - scale * step;
      Eigen::Matrix2d J_candidate;
      const Eigen::Vector2d candidate_residual = Distort(candidate, &J_candidate) - xy_d;
      if (candidate_residual.norm() < residual_norm) {
        xy = candidate;
        J = J_candidate;
        residual = candidate_residual;
        residual_norm = residual.norm();
        improved = true;
      }
    }
    if (!improved) break;  // at the floating-point floor (or beyond the fold)
  }
  return Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
}

std::unique_ptr<CameraModel> RadTanCamera::Scaled(int new_width, int new_height) const {
  return std::make_unique<RadTanCamera>(new_width, new_height,
                                        k_.Scaled(static_cast<double>(new_width) / width(),
                                                  static_cast<double>(new_height) / height()),
                                        d_);
}

std::unique_ptr<CameraModel> RadTanCamera::Clone() const {
  return std::make_unique<RadTanCamera>(*this);
}

}  // namespace aperture::perception
