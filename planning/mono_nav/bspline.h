#pragma once
// A clamped B-spline curve in R^3, s(t) = sum_j P_j B_j^p(t) (seed 003 Sec. III-E (15)), with its
// derivatives from the basis-function derivatives of Piegl & Tiller, The NURBS Book, Alg. A2.2
// (span search) and A2.3 (derivatives of the basis functions). Also the global interpolation /
// least-squares fits with knots by averaging (The NURBS Book (9.8)).
#include <Eigen/Core>
#include <vector>

namespace aperture::planning {

class BSpline {
 public:
  using ControlPoints = Eigen::Matrix<double, Eigen::Dynamic, 3>;

  // `knots`: non-decreasing, size = control points + degree + 1, clamped (first and last knot
  // repeated degree + 1 times). Throws std::invalid_argument otherwise.
  BSpline(int degree, std::vector<double> knots, ControlPoints control_points);

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  const ControlPoints& control_points() const { return control_points_; }
  double StartParameter() const { return knots_.front(); }
  double EndParameter() const { return knots_.back(); }

  // d^k s / dt^k at t (clamped into the parameter range); k = 0 .. degree.
  Eigen::Vector3d Evaluate(double t, int derivative = 0) const;
  // Row of the k-th derivatives of all basis functions at t: s^(k)(t) = Row * P.
  Eigen::RowVectorXd BasisRow(double t, int derivative) const;
  // The same curve with its parameter stretched by `factor` (t' = t0 + factor (t - t0)): the
  // k-th derivative shrinks by factor^k.
  BSpline TimeScaled(double factor) const;

  // Clamped knots for `count` control points of `degree` at the data parameters `params`
  // (increasing, size >= count) by averaging (The NURBS Book (9.8), generalised to least squares).
  static std::vector<double> AveragedKnots(const std::vector<double>& params, int degree,
                                           int count);

 private:
  int Span(double t) const;

  int degree_;
  std::vector<double> knots_;
  ControlPoints control_points_;
};

}  // namespace aperture::planning
