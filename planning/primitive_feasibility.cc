#include "planning/primitive_feasibility.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::planning {
namespace {

// Per-primitive data shared by all sections: the interior candidates for extrema of each axis of
// a(t) - g (roots of j_i) and of j_i (vertex of the parabola), computed once.
struct SectionChecker {
  const MotionPrimitive& primitive;
  const FeasibilityLimits& limits;
  Eigen::Vector3d c0;  // a0 - g: thrust vector at t = 0
  double thrust_extremum_t[3][2];
  int thrust_extremum_count[3];
  double jerk_vertex_t[3];
  bool jerk_has_vertex[3];

  SectionChecker(const MotionPrimitive& p, const FeasibilityLimits& l) : primitive(p), limits(l) {
    c0 = p.initial_acceleration_W() + Eigen::Vector3d(0.0, 0.0, l.gravity_mps2);
    for (int i = 0; i < 3; ++i) {
      const double a = 0.5 * p.alpha()[i], b = p.beta()[i], c = p.gamma()[i];
      int count = 0;
      if (a != 0.0) {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
          // Numerically stable quadratic roots.
          const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
          thrust_extremum_t[i][count++] = q / a;
          if (q != 0.0) thrust_extremum_t[i][count++] = c / q;
        }
      } else if (b != 0.0) {
        thrust_extremum_t[i][count++] = -c / b;
      }
      thrust_extremum_count[i] = count;
      jerk_has_vertex[i] = p.alpha()[i] != 0.0;
      jerk_vertex_t[i] = jerk_has_vertex[i] ? -p.beta()[i] / p.alpha()[i] : 0.0;
    }
  }

  double ThrustComponent(int i, double t) const {
    return c0[i] + t * (primitive.gamma()[i] +
                        t * (0.5 * primitive.beta()[i] + t * primitive.alpha()[i] / 6.0));
  }
  double JerkComponent(int i, double t) const {
    return primitive.gamma()[i] + t * (primitive.beta()[i] + 0.5 * t * primitive.alpha()[i]);
  }
  Eigen::Vector3d ThrustVector(double t) const {
    return Eigen::Vector3d(ThrustComponent(0, t), ThrustComponent(1, t), ThrustComponent(2, t));
  }

  // c1, c2: thrust vectors at t1, t2 (passed in so that split points are evaluated once).
  Feasibility Check(double t1, double t2, const Eigen::Vector3d& c1,
                    const Eigen::Vector3d& c2) const {
    const double f_max = limits.max_thrust_mps2, f_min = limits.min_thrust_mps2;
    // True values at the ends prove infeasibility.
    const double f1_sq = c1.squaredNorm(), f2_sq = c2.squaredNorm();
    if (std::max(f1_sq, f2_sq) > f_max * f_max) return Feasibility::kInfeasibleThrustHigh;
    if (std::min(f1_sq, f2_sq) < f_min * f_min) return Feasibility::kInfeasibleThrustLow;

    double upper_sq = 0.0, lower_sq = 0.0, jerk_sq = 0.0;
    for (int i = 0; i < 3; ++i) {
      double lo = std::min(c1[i], c2[i]), hi = std::max(c1[i], c2[i]);
      for (int r = 0; r < thrust_extremum_count[i]; ++r) {
        const double t = thrust_extremum_t[i][r];
        if (t > t1 && t < t2) {
          const double c = ThrustComponent(i, t);
          lo = std::min(lo, c);
          hi = std::max(hi, c);
        }
      }
      const double magnitude = std::max(-lo, hi);
      // At the extremum f >= |c_i| > f_max: a true point outside the limits.
      if (magnitude > f_max) return Feasibility::kInfeasibleThrustHigh;
      upper_sq += magnitude * magnitude;
      const double distance_from_zero = lo > 0.0 ? lo : (hi < 0.0 ? -hi : 0.0);
      lower_sq += distance_from_zero * distance_from_zero;

      double j_abs = std::max(std::abs(JerkComponent(i, t1)), std::abs(JerkComponent(i, t2)));
      if (jerk_has_vertex[i] && jerk_vertex_t[i] > t1 && jerk_vertex_t[i] < t2) {
        j_abs = std::max(j_abs, std::abs(JerkComponent(i, jerk_vertex_t[i])));
      }
      jerk_sq += j_abs * j_abs;
    }
    // |omega| <= |j| / f <= jbar / f_lower (the note's step 2).
    if (upper_sq <= f_max * f_max && lower_sq >= f_min * f_min &&
        jerk_sq <= limits.max_body_rate_radps * limits.max_body_rate_radps * lower_sq) {
      return Feasibility::kFeasible;
    }
    if (t2 - t1 < 2.0 * limits.min_section_duration_s) return Feasibility::kIndeterminable;

    const double t_mid = 0.5 * (t1 + t2);
    const Eigen::Vector3d c_mid = ThrustVector(t_mid);
    const Feasibility first = Check(t1, t_mid, c1, c_mid);
    if (first == Feasibility::kInfeasibleThrustHigh || first == Feasibility::kInfeasibleThrustLow) {
      return first;
    }
    const Feasibility second = Check(t_mid, t2, c_mid, c2);
    if (second != Feasibility::kFeasible) return second;
    return first;
  }
};

// Polynomial c[0] + c[1] t + ... + c[degree] t^degree.
double EvaluatePolynomial(const double* c, int degree, double t) {
  double value = c[degree];
  for (int i = degree - 1; i >= 0; --i) value = value * t + c[i];
  return value;
}

// Real roots of the polynomial in (a, b), ascending, into roots (at most degree of them); returns
// the count. Between consecutive roots of the derivative the polynomial is monotone, so each such
// interval holds at most one root, found by bisection to double precision.
int RootsInInterval(const double* c, int degree, double a, double b, double* roots) {
  if (degree == 0) return 0;
  if (degree == 1) {
    if (c[1] == 0.0) return 0;
    const double t = -c[0] / c[1];
    roots[0] = t;
    return (t > a && t < b) ? 1 : 0;
  }
  double derivative[5];
  for (int i = 1; i <= degree; ++i) derivative[i - 1] = i * c[i];
  double breaks[6];
  int count = 0;
  breaks[count++] = a;
  count += RootsInInterval(derivative, degree - 1, a, b, breaks + 1);
  breaks[count++] = b;
  int found = 0;
  for (int k = 0; k + 1 < count; ++k) {
    double lo = breaks[k], hi = breaks[k + 1];
    double f_lo = EvaluatePolynomial(c, degree, lo);
    const double f_hi = EvaluatePolynomial(c, degree, hi);
    if (f_lo == 0.0 && k > 0) {
      roots[found++] = lo;  // a root at an interior break (double root)
      continue;
    }
    if ((f_lo < 0.0) == (f_hi < 0.0) || f_hi == 0.0) continue;
    for (int iteration = 0; iteration < 200 && hi - lo > 0.0; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      const double f_mid = EvaluatePolynomial(c, degree, mid);
      if ((f_mid < 0.0) == (f_lo < 0.0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    roots[found++] = 0.5 * (lo + hi);
  }
  return found;
}

}  // namespace

double MinimumProjection(const MotionPrimitive& primitive, const Eigen::Vector3d& normal_W) {
  const Eigen::Vector3d& n = normal_W;
  const double q[6] = {n.dot(primitive.initial_position_W()),
                       n.dot(primitive.initial_velocity_W()),
                       n.dot(primitive.initial_acceleration_W()) / 2.0,
                       n.dot(primitive.gamma()) / 6.0,
                       n.dot(primitive.beta()) / 24.0,
                       n.dot(primitive.alpha()) / 120.0};
  const double dq[5] = {q[1], 2.0 * q[2], 3.0 * q[3], 4.0 * q[4], 5.0 * q[5]};
  const double T = primitive.duration_s();
  double minimum = std::min(q[0], EvaluatePolynomial(q, 5, T));
  double roots[4];
  const int count = RootsInInterval(dq, 4, 0.0, T, roots);
  for (int i = 0; i < count; ++i) minimum = std::min(minimum, EvaluatePolynomial(q, 5, roots[i]));
  return minimum;
}

FeasibilityLimits FeasibilityLimits::FromVehicle(const control::VehicleParameters& vehicle,
                                                 double max_body_rate_radps) {
  vehicle.Validate();
  FeasibilityLimits limits;
  limits.min_thrust_mps2 = 4.0 * vehicle.rotor.MinThrust() / vehicle.mass_kg;
  limits.max_thrust_mps2 = 4.0 * vehicle.rotor.MaxThrust() / vehicle.mass_kg;
  limits.max_body_rate_radps = max_body_rate_radps;
  limits.gravity_mps2 = vehicle.gravity_mps2;
  limits.Validate();
  return limits;
}

void FeasibilityLimits::Validate() const {
  auto require = [](bool ok, const char* field, double value, const char* fix) {
    if (!ok) {
      throw std::invalid_argument(std::string("FeasibilityLimits: ") + field + " = " +
                                  std::to_string(value) + " " + fix);
    }
  };
  require(std::isfinite(min_thrust_mps2) && min_thrust_mps2 >= 0.0, "min_thrust_mps2",
          min_thrust_mps2, "must be finite and >= 0");
  require(std::isfinite(max_thrust_mps2) && max_thrust_mps2 > min_thrust_mps2, "max_thrust_mps2",
          max_thrust_mps2, "must be finite and greater than min_thrust_mps2");
  require(std::isfinite(max_body_rate_radps) && max_body_rate_radps > 0.0, "max_body_rate_radps",
          max_body_rate_radps, "must be finite and > 0");
  require(std::isfinite(min_section_duration_s) && min_section_duration_s > 0.0,
          "min_section_duration_s", min_section_duration_s, "must be finite and > 0");
  require(std::isfinite(gravity_mps2) && gravity_mps2 > 0.0, "gravity_mps2", gravity_mps2,
          "must be finite and > 0");
}

const char* ToString(Feasibility feasibility) {
  switch (feasibility) {
    case Feasibility::kFeasible:
      return "feasible";
    case Feasibility::kInfeasibleThrustHigh:
      return "infeasible (thrust above f_max)";
    case Feasibility::kInfeasibleThrustLow:
      return "infeasible (thrust below f_min)";
    case Feasibility::kIndeterminable:
      return "indeterminable";
  }
  return "unknown";
}

Feasibility CheckInputFeasibility(const MotionPrimitive& primitive,
                                  const FeasibilityLimits& limits) {
  const SectionChecker checker(primitive, limits);
  const double T = primitive.duration_s();
  return checker.Check(0.0, T, checker.ThrustVector(0.0), checker.ThrustVector(T));
}

}  // namespace aperture::planning
