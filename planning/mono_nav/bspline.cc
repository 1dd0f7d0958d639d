#include "planning/mono_nav/bspline.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace aperture::planning {

BSpline::BSpline(int degree, std::vector<double> knots, ControlPoints control_points)
    : degree_(degree), knots_(std::move(knots)), control_points_(std::move(control_points)) {
  const int count = static_cast<int>(control_points_.rows());
  if (degree_ < 1 || count < degree_ + 1 || int(knots_.size()) != count + degree_ + 1) {
    throw std::invalid_argument(
        "BSpline: need degree >= 1, at least degree + 1 control points and "
        "control points + degree + 1 knots");
  }
  for (std::size_t i = 1; i < knots_.size(); ++i) {
    if (!(knots_[i] >= knots_[i - 1]))
      throw std::invalid_argument("BSpline: knots must not decrease");
  }
  for (int i = 1; i <= degree_; ++i) {
    if (knots_[i] != knots_[0] || knots_[knots_.size() - 1 - i] != knots_.back()) {
      throw std::invalid_argument(
          "BSpline: knots must be clamped (end knots repeated degree + 1 "
          "times)");
    }
  }
  if (!(knots_.back() > knots_.front()) || !control_points_.allFinite()) {
    throw std::invalid_argument("BSpline: empty parameter range or non-finite control points");
  }
}

int BSpline::Span(double t) const {  // The NURBS Book A2.2
  const int n = static_cast<int>(control_points_.rows()) - 1;
  if (t >= knots_[n + 1]) return n;
  if (t <= knots_[degree_]) return degree_;
  const auto it = std::upper_bound(knots_.begin() + degree_, knots_.begin() + n + 1, t);
  return static_cast<int>(it - knots_.begin()) - 1;
}

Eigen::RowVectorXd BSpline::BasisRow(double t, int derivative) const {
  const int p = degree_;
  if (derivative < 0 || derivative > p) {
    throw std::invalid_argument("BSpline: derivative order " + std::to_string(derivative) +
                                " not in [0, degree]");
  }
  t = std::clamp(t, knots_.front(), knots_.back());
  const int span = Span(t);
  // The NURBS Book A2.3: ndu holds basis functions (upper triangle) and knot differences (lower).
  Eigen::MatrixXd ndu(p + 1, p + 1), a(2, p + 1),
      ders = Eigen::MatrixXd::Zero(derivative + 1, p + 1);
  Eigen::VectorXd left(p + 1), right(p + 1);
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots_[span + 1 - j];
    right[j] = knots_[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = right[r + 1] + left[j - r];
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders(0, j) = ndu(j, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a(0, 0) = 1.0;
    for (int k = 1; k <= derivative; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
        d += a(s2, k) * ndu(r, pk);
      }
      ders(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= derivative; ++k) {
    ders.row(k) *= factor;
    factor *= p - k;
  }
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(control_points_.rows());
  row.segment(span - p, p + 1) = ders.row(derivative);
  return row;
}

Eigen::Vector3d BSpline::Evaluate(double t, int derivative) const {
  return (BasisRow(t, derivative) * control_points_).transpose();
}

BSpline BSpline::TimeScaled(double factor) const {
  if (!(factor > 0.0)) throw std::invalid_argument("BSpline: time scale factor must be > 0");
  std::vector<double> knots = knots_;
  for (double& knot : knots) knot = knots_.front() + factor * (knot - knots_.front());
  return BSpline(degree_, std::move(knots), control_points_);
}

std::vector<double> BSpline::AveragedKnots(const std::vector<double>& params, int degree,
                                           int count) {
  const int m = static_cast<int>(params.size());
  if (count < degree + 1 || m < count) {
    throw std::invalid_argument(
        "BSpline::AveragedKnots: need degree + 1 <= control points <= "
        "data points");
  }
  std::vector<double> knots(count + degree + 1);
  std::fill(knots.begin(), knots.begin() + degree + 1, params.front());
  std::fill(knots.end() - degree - 1, knots.end(), params.back());
  // Interior knots: averages of `degree` consecutive parameters, taken at evenly spread positions
  // of the data when there are more data than control points (least squares).
  const double step = double(m - 1) / double(count - 1);
  for (int j = 1; j < count - degree; ++j) {
    double sum = 0.0;
    for (int i = j; i < j + degree; ++i) {
      const double position = std::min(double(m - 1), i * step);
      const int lo = static_cast<int>(position);
      const int hi = std::min(m - 1, lo + 1);
      sum += params[lo] + (position - lo) * (params[hi] - params[lo]);
    }
    knots[j + degree] = sum / degree;
  }
  return knots;
}

}  // namespace aperture::planning
