#include "perception/tags/ippe_square.h"

#include <Eigen/LU>
#include <cmath>

namespace aperture::perception {
namespace {

// The tag's corners on a square of half-edge 1 (TagCorner's order), for a well-conditioned DLT.
constexpr double kUnitCorners[4][2] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};

// Homography H (H(2,2) = 1) with u ~ H [x; y; 1] from the unit square to the image: the 8x8
// direct linear system of four correspondences.
std::optional<Eigen::Matrix3d> UnitSquareHomography(
    const std::array<Eigen::Vector2d, 4>& corners_normalized) {
  Eigen::Matrix<double, 8, 8> M;
  Eigen::Matrix<double, 8, 1> rhs;
  for (int k = 0; k < 4; ++k) {
    const double x = kUnitCorners[k][0], y = kUnitCorners[k][1];
    const double u = corners_normalized[k].x(), v = corners_normalized[k].y();
    M.row(2 * k) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    M.row(2 * k + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    rhs(2 * k) = u;
    rhs(2 * k + 1) = v;
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 8, 8>> lu(M);
  if (!lu.isInvertible()) return std::nullopt;
  const Eigen::Matrix<double, 8, 1> h = lu.solve(rhs);
  Eigen::Matrix3d H;
  H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0;
  // Three collinear corners solve the system with a singular H (the square maps onto a line).
  constexpr double kMinRelativeDeterminant = 1e-10;
  if (!(std::abs(H.determinant()) > kMinRelativeDeterminant * std::pow(H.norm(), 3))) {
    return std::nullopt;
  }
  return H;
}

// Translation minimizing the algebraic reprojection error of the corners p_T given R_CT:
// (R p + t)_x - u (R p + t)_z = 0 and likewise for v, linear in t.
Eigen::Vector3d FitTranslation(const Eigen::Matrix3d& R_CT,
                               const std::array<Eigen::Vector2d, 4>& corners_normalized,
                               double half_edge_m) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d q = R_CT * Eigen::Vector3d(half_edge_m * kUnitCorners[k][0],
                                                     half_edge_m * kUnitCorners[k][1], 0.0);
    for (int axis = 0; axis < 2; ++axis) {
      const double u = corners_normalized[k](axis);
      Eigen::RowVector3d row = Eigen::RowVector3d::Zero();
      row(axis) = 1.0;
      row(2) = -u;
      const double b = u * q.z() - q(axis);
      normal += row.transpose() * row;
      rhs += row.transpose() * b;
    }
  }
  return normal.ldlt().solve(rhs);
}

}  // namespace

std::optional<std::array<Eigen::Isometry3d, 2>> IppeSquare(
    const std::array<Eigen::Vector2d, 4>& corners_normalized, double tag_size_m) {
  const std::optional<Eigen::Matrix3d> H = UnitSquareHomography(corners_normalized);
  if (!H) return std::nullopt;
  // Image point v of the tag centre and the Jacobian of the homography there, per metre of the
  // tag plane (the unit square's coordinates are metres * 2 / tag_size_m).
  const Eigen::Vector2d v(H->coeff(0, 2), H->coeff(1, 2));
  Eigen::Matrix2d J;
  J << H->coeff(0, 0) - v.x() * H->coeff(2, 0), H->coeff(0, 1) - v.x() * H->coeff(2, 1),
      H->coeff(1, 0) - v.y() * H->coeff(2, 0), H->coeff(1, 1) - v.y() * H->coeff(2, 1);
  J *= 2.0 / tag_size_m;

  const Eigen::Matrix3d R_v =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), v.homogeneous())
          .toRotationMatrix();
  Eigen::Matrix<double, 2, 3> project_at_v;
  project_at_v << 1.0, 0.0, -v.x(), 0.0, 1.0, -v.y();
  const Eigen::Matrix2d B = (project_at_v * R_v).leftCols<2>();
  const Eigen::Matrix2d A = B.inverse() * J;
  // Largest singular value of the 2x2 A in closed form.
  const double frobenius_sq = A.squaredNorm();
  const double det = A.determinant();
  const double gamma = std::sqrt(
      0.5 * (frobenius_sq + std::sqrt(std::max(0.0, frobenius_sq * frobenius_sq - 4 * det * det))));
  if (!(gamma > 0.0) || !std::isfinite(gamma)) return std::nullopt;
  const Eigen::Matrix2d R22 = A / gamma;
  const Eigen::Matrix2d bbT = Eigen::Matrix2d::Identity() - R22.transpose() * R22;
  const double b0 = std::sqrt(std::max(0.0, bbT(0, 0)));
  const double b1 = std::copysign(std::sqrt(std::max(0.0, bbT(1, 1))), bbT(0, 1));

  std::array<Eigen::Isometry3d, 2> T_CT;
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d c0(R22(0, 0), R22(1, 0), sign * b0);
    const Eigen::Vector3d c1(R22(0, 1), R22(1, 1), sign * b1);
    Eigen::Matrix3d R_tilde;
    R_tilde << c0, c1, c0.cross(c1);
    T_CT[s].setIdentity();
    T_CT[s].linear() = R_v * R_tilde;
    T_CT[s].translation() = FitTranslation(T_CT[s].linear(), corners_normalized, 0.5 * tag_size_m);
    if (!T_CT[s].matrix().allFinite()) return std::nullopt;
  }
  return T_CT;
}

}  // namespace aperture::perception
