#include "perception/led/p3p_solver.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opengv/absolute_pose/modules/main.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

// Kneip, Scaramuzza, Siegwart, CVPR 2011 through OpenGV (reference implementation).
void SolveOpenGv(const std::array<Eigen::Vector3d, 3>& f_C,
                 const std::array<Eigen::Vector3d, 3>& p_T,
                 std::vector<Eigen::Isometry3d>* solutions) {
  opengv::bearingVectors_t bearings(f_C.begin(), f_C.end());
  opengv::points_t points(p_T.begin(), p_T.end());
  opengv::transformations_t poses;
  opengv::absolute_pose::modules::p3p_kneip_main(bearings, points, poses);
  for (const auto& T_TC : poses) {  // OpenGV returns [R_TC | p_TC]
    if (!T_TC.allFinite()) continue;
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    T_CT.linear() = T_TC.leftCols<3>().transpose();
    T_CT.translation() = -T_CT.linear() * T_TC.col(3);
    solutions->push_back(T_CT);
  }
}

// Largest real root of m^3 + a m^2 + b m + c (closed form: trigonometric with three real roots,
// Cardano with one).
double LargestCubicRoot(double a, double b, double c) {
  const double Q = (a * a - 3.0 * b) / 9.0;
  const double R = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
  const double Q3 = Q * Q * Q;
  if (R * R < Q3) {
    const double theta = std::acos(std::clamp(R / std::sqrt(Q3), -1.0, 1.0));
    return -2.0 * std::sqrt(Q) * std::cos((theta - 2.0 * M_PI) / 3.0) - a / 3.0;
  }
  const double S = -std::copysign(std::cbrt(std::abs(R) + std::sqrt(R * R - Q3)), R);
  return S + (S != 0.0 ? Q / S : 0.0) - a / 3.0;
}

// Appends the real roots of x^2 + b x + c. A discriminant negative by round-off only (a double
// root split into a complex pair by noise) counts as zero.
void AppendQuadraticRoots(double b, double c, double* roots, int* count) {
  double discriminant = b * b - 4.0 * c;
  if (discriminant < 0.0) {
    if (discriminant < -1e-12 * (b * b + std::abs(c) + 1.0)) return;
    discriminant = 0.0;
  }
  const double root = std::sqrt(discriminant);
  // Numerically stable pair: q = -(b + sign(b) root) / 2, x = q and c / q.
  const double q = -0.5 * (b + std::copysign(root, b));
  roots[(*count)++] = q;
  if (q != 0.0) roots[(*count)++] = c / q;
}

// Real roots of a[0] x^4 + ... + a[4] (a[0] != 0) by Ferrari's method in real arithmetic: the
// depressed quartic y^4 + p y^2 + q y + r splits into two quadratics through the positive root m
// of its resolvent cubic; each root is then polished by two Newton steps on the original
// polynomial. Returns the count (<= 4).
int RealQuarticRoots(const std::array<double, 5>& a, double* roots) {
  const double b = a[1] / a[0], c = a[2] / a[0], d = a[3] / a[0], e = a[4] / a[0];
  const double b2 = b * b;
  const double p = c - 3.0 * b2 / 8.0;
  const double q = d - b * c / 2.0 + b2 * b / 8.0;
  const double r = e - b * d / 4.0 + b2 * c / 16.0 - 3.0 * b2 * b2 / 256.0;
  int count = 0;
  if (std::abs(q) < 1e-14 * (1.0 + std::abs(p) + std::abs(r))) {
    // Biquadratic: y^2 = z with z^2 + p z + r = 0.
    double z[2];
    int z_count = 0;
    AppendQuadraticRoots(p, r, z, &z_count);
    for (int k = 0; k < z_count; ++k) {
      if (z[k] < 0.0) continue;
      roots[count++] = std::sqrt(z[k]);
      roots[count++] = -std::sqrt(z[k]);
    }
  } else {
    // Resolvent m^3 + p m^2 + (p^2/4 - r) m - q^2/8: negative at 0, so its largest root is > 0.
    double m = LargestCubicRoot(p, p * p / 4.0 - r, -q * q / 8.0);
    if (!(m > 0.0)) return 0;
    const double s = std::sqrt(2.0 * m);
    AppendQuadraticRoots(-s, p / 2.0 + m + q / (2.0 * s), roots, &count);
    AppendQuadraticRoots(s, p / 2.0 + m - q / (2.0 * s), roots, &count);
  }
  for (int k = 0; k < count; ++k) {
    double x = roots[k] - b / 4.0;
    for (int step = 0; step < 2; ++step) {
      const double value = (((x + b) * x + c) * x + d) * x + e;
      const double slope = ((4.0 * x + 3.0 * b) * x + 2.0 * c) * x + d;
      if (slope == 0.0) break;
      x -= value / slope;
    }
    roots[k] = x;
  }
  return count;
}

// Kneip, Scaramuzza, Siegwart, "A Novel Parametrization of the Perspective-Three-Point Problem
// for a Direct Computation of Absolute Camera Position and Orientation", CVPR 2011: intermediate
// camera frame tau (from f_1, f_2) and object frame eta (from P_1, P_2, P_3), a quartic in
// cos(theta) (the angle of the plane through the camera centre, P_1 and P_2), then alpha and the
// pose in closed form. Here the quartic's real roots come from Ferrari's method in real
// arithmetic with fixed-size buffers: faster than OpenGV's complex-root version and no allocation
// (the brute-force correspondence search calls it thousands of times per frame).
void SolveKneip(const std::array<Eigen::Vector3d, 3>& f_C,
                const std::array<Eigen::Vector3d, 3>& p_T,
                std::vector<Eigen::Isometry3d>* solutions) {
  int i1 = 0, i2 = 1;
  Eigen::Vector3d e3 = f_C[0].cross(f_C[1]);
  if (e3.squaredNorm() == 0.0) return;  // parallel bearings
  e3.normalize();
  // tau frame: e1 = f_1, e3 normal to f_1 and f_2. theta must come out in [0, pi]: f_3 on the
  // negative e3 side, else swap points 1 and 2.
  if (e3.dot(f_C[2]) > 0.0) {
    std::swap(i1, i2);
    e3 = -e3;
  }
  const Eigen::Vector3d& f1 = f_C[i1];
  const Eigen::Vector3d& f2 = f_C[i2];
  Eigen::Matrix3d T_tau;  // rows e1, e2, e3: C -> tau
  T_tau.row(0) = f1;
  T_tau.row(1) = e3.cross(f1);
  T_tau.row(2) = e3;
  const Eigen::Vector3d f3_tau = T_tau * f_C[2];

  const Eigen::Vector3d& P1 = p_T[i1];
  const Eigen::Vector3d P12 = p_T[i2] - P1;
  const Eigen::Vector3d P13 = p_T[2] - P1;
  Eigen::Vector3d n3 = P12.cross(P13);
  if (n3.squaredNorm() == 0.0) return;  // collinear points
  const double d = P12.norm();
  Eigen::Matrix3d N;  // rows n1, n2, n3: T -> eta (origin P_1)
  N.row(0) = P12 / d;
  N.row(2) = n3.normalized();
  N.row(1) = N.row(2).cross(N.row(0));
  const Eigen::Vector3d P3_eta = N * P13;

  const double phi1 = f3_tau.x() / f3_tau.z(), phi2 = f3_tau.y() / f3_tau.z();
  const double p1 = P3_eta.x(), p2 = P3_eta.y();
  const double cos_beta = f1.dot(f2);
  // b = cot(beta), beta the angle between f_1 and f_2.
  const double b = std::copysign(std::sqrt(1.0 / (1.0 - cos_beta * cos_beta) - 1.0), cos_beta);
  const double phi1_2 = phi1 * phi1, phi2_2 = phi2 * phi2;
  const double p1_2 = p1 * p1, p2_2 = p2 * p2, d_2 = d * d, b_2 = b * b;
  // Quartic a4 x^4 + ... + a0 in x = cos(theta) (Kneip 2011, the paper's coefficients grouped).
  const std::array<double, 5> a{
      -p2_2 * p2_2 * (phi1_2 + phi2_2 + 1.0),
      2.0 * p2_2 * p2 * d * (b * (1.0 + phi2_2) - phi1 * phi2),
      p2_2 * (p2_2 * (phi1_2 + phi2_2) - p1_2 * (phi1_2 + phi2_2 + 2.0) -
              d_2 * (b_2 * (phi2_2 + 1.0) + phi2_2) + 2.0 * p1 * d * (1.0 + phi2_2) +
              2.0 * phi1 * phi2 * p1 * d * b),
      2.0 * p2 * d * (p1_2 * b + p2_2 * phi2 * (phi1 - phi2 * b) - p1 * d * b),
      phi2_2 * p2_2 * ((p1 - d) * (p1 - d) + d_2 * b_2) + p2_2 * phi1_2 * p1_2 -
          2.0 * phi1 * phi2 * p1 * p2_2 * d * b + 2.0 * p1_2 * p1 * d - p1_2 * d_2 -
          p1_2 * p1_2};
  if (a[0] == 0.0 || !std::isfinite(a[0])) return;
  double roots[4];
  const int root_count = RealQuarticRoots(a, roots);
  const Eigen::Matrix3d N_T = N.transpose();
  for (int r = 0; r < root_count; ++r) {
    // cos(theta): a root outside [-1, 1] beyond round-off is no pose.
    if (!(std::abs(roots[r]) <= 1.0 + 1e-9)) continue;
    const double cos_theta = std::clamp(roots[r], -1.0, 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double cot_alpha = (-phi1 * p1 / phi2 - cos_theta * p2 + d * b) /
                             (-phi1 * cos_theta * p2 / phi2 + p1 - d);
    if (!std::isfinite(cot_alpha)) continue;
    const double sin_alpha = std::sqrt(1.0 / (cot_alpha * cot_alpha + 1.0));
    const double cos_alpha = std::copysign(std::sqrt(1.0 - sin_alpha * sin_alpha), cot_alpha);
    // Camera centre in eta, then in T.
    const double k = d * (sin_alpha * b + cos_alpha);
    const Eigen::Vector3d C_eta(cos_alpha * k, cos_theta * sin_alpha * k,
                                sin_theta * sin_alpha * k);
    const Eigen::Vector3d p_TC = P1 + N_T * C_eta;
    // Rotation eta -> tau (the paper's Q), so R_TC = N^T Q^T T_tau.
    Eigen::Matrix3d Q;
    Q << -cos_alpha, -sin_alpha * cos_theta, -sin_alpha * sin_theta,  //
        sin_alpha, -cos_alpha * cos_theta, -cos_alpha * sin_theta,     //
        0.0, -sin_theta, cos_theta;
    const Eigen::Matrix3d R_TC = N_T * Q.transpose() * T_tau;
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    T_CT.linear() = R_TC.transpose();
    T_CT.translation() = -R_TC.transpose() * p_TC;
    if (T_CT.matrix().allFinite()) solutions->push_back(T_CT);
  }
}

void SolveAp3p(const std::array<Eigen::Vector3d, 3>& f_C,
               const std::array<Eigen::Vector3d, 3>& p_T,
               std::vector<Eigen::Isometry3d>* solutions) {
  cv::Matx<double, 3, 3> object;
  cv::Matx<double, 3, 2> image;
  for (int i = 0; i < 3; ++i) {
    if (f_C[i].z() <= 1e-9) return;  // AP3P works on normalized image points only
    for (int k = 0; k < 3; ++k) object(i, k) = p_T[i][k];
    image(i, 0) = f_C[i].x() / f_C[i].z();
    image(i, 1) = f_C[i].y() / f_C[i].z();
  }
  std::vector<cv::Mat> rvecs, tvecs;
  const cv::Matx33d K = cv::Matx33d::eye();
  cv::solveP3P(cv::Mat(object).reshape(3, 3), cv::Mat(image).reshape(2, 3), K, cv::noArray(),
               rvecs, tvecs, cv::SOLVEPNP_AP3P);
  for (std::size_t s = 0; s < rvecs.size(); ++s) {
    cv::Matx33d R;
    cv::Rodrigues(rvecs[s], R);
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T_CT.linear()(r, c) = R(r, c);
      T_CT.translation()[r] = tvecs[s].at<double>(r);
    }
    if (T_CT.matrix().allFinite()) solutions->push_back(T_CT);
  }
}

}  // namespace

P3pMethod ParseP3pMethod(const std::string& name) {
  if (name == "kneip") return P3pMethod::kKneip;
  if (name == "opengv") return P3pMethod::kOpenGv;
  if (name == "ap3p") return P3pMethod::kAp3p;
  throw std::invalid_argument("unknown P3P method '" + name + "'; use kneip, opengv or ap3p");
}

std::string P3pMethodName(P3pMethod method) {
  switch (method) {
    case P3pMethod::kKneip: return "kneip";
    case P3pMethod::kOpenGv: return "opengv";
    case P3pMethod::kAp3p: return "ap3p";
  }
  return "unknown";
}

void SolveP3p(P3pMethod method, const std::array<Eigen::Vector3d, 3>& f_C,
              const std::array<Eigen::Vector3d, 3>& p_T,
              std::vector<Eigen::Isometry3d>* solutions) {
  solutions->clear();
  switch (method) {
    case P3pMethod::kKneip: SolveKneip(f_C, p_T, solutions); break;
    case P3pMethod::kOpenGv: SolveOpenGv(f_C, p_T, solutions); break;
    case P3pMethod::kAp3p: SolveAp3p(f_C, p_T, solutions); break;
  }
  // Both solvers turn near-real complex roots of their quartic into poses that do not reproduce
  // the bearings; drop them (and points behind the camera centre) so that callers only vote
  // with true solutions. 1e-4 rad is far above the round-off of a genuine solution.
  constexpr double kMaxBearingError_rad = 1e-4;
  solutions->erase(
      std::remove_if(solutions->begin(), solutions->end(),
                     [&](const Eigen::Isometry3d& T_CT) {
                       for (int i = 0; i < 3; ++i) {
                         const Eigen::Vector3d p_C = T_CT * p_T[i];
                         if (p_C.cross(f_C[i]).norm() > kMaxBearingError_rad * p_C.norm() ||
                             p_C.dot(f_C[i]) <= 0.0) {
                           return true;
                         }
                       }
                       return false;
                     }),
      solutions->end());
}

}  // namespace aperture::perception
