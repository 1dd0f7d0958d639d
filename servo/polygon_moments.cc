#include "servo/polygon_moments.h"

namespace aperture::servo {
namespace {

constexpr int kMaxOrder = 3;

double Binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

}  // namespace

Eigen::Matrix4d PolygonMoments(const std::vector<Eigen::Vector2d>& polygon) {
  // Powers x^0..x^3 of each edge's end points, then the double sum of the formula in the header per
  // (p, q).
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % n];
    const double cross = a.x() * b.y() - b.x() * a.y();
    double xa[kMaxOrder + 1], xb[kMaxOrder + 1], ya[kMaxOrder + 1], yb[kMaxOrder + 1];
    xa[0] = xb[0] = ya[0] = yb[0] = 1.0;
    for (int e = 1; e <= kMaxOrder; ++e) {
      xa[e] = xa[e - 1] * a.x();
      xb[e] = xb[e - 1] * b.x();
      ya[e] = ya[e - 1] * a.y();
      yb[e] = yb[e - 1] * b.y();
    }
    for (int p = 0; p <= kMaxOrder; ++p) {
      for (int q = 0; p + q <= kMaxOrder; ++q) {
        double sum = 0.0;
        for (int i = 0; i <= p; ++i) {
          for (int j = 0; j <= q; ++j) {
            sum += Binomial(i + j, i) * Binomial(p + q - i - j, p - i) * xa[i] * xb[p - i] * ya[j] *
                   yb[q - j];
          }
        }
        m(p, q) += cross * sum;
      }
    }
  }
  for (int p = 0; p <= kMaxOrder; ++p) {
    for (int q = 0; p + q <= kMaxOrder; ++q) {
      m(p, q) /= (p + q + 2) * (p + q + 1) * Binomial(p + q, p);
    }
  }
  if (m(0, 0) < 0.0) m = -m;  // clockwise in x-y: the same integrals with the opposite sign
  return m;
}

}  // namespace aperture::servo
