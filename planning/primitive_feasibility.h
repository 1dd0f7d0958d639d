#pragma once
// Recursive input-feasibility test of a MotionPrimitive (Mueller, Hehn & D'Andrea 2015, as stated
// in notes/motion_primitive.md). Inputs are the mass-normalised collective thrust
// f(t) = |a(t) - g| (g = (0, 0, -gravity) in W) and the body rates, bounded through
// |omega(t)| <= |j(t)| / f(t) (jerk normal to the thrust direction over f; yaw rate excluded).
// On a section [t1, t2] the test bounds every axis of a - g (a cubic) and of j (a quadratic) by its
// values at the ends and at its interior extrema; from these it bounds f from above and below and
// |omega| from above. A section inside the limits is feasible; a point of the section outside
// the thrust limits (an end, or an axis extremum whose single component already exceeds f_max)
// proves infeasibility; otherwise the section is halved, down to a minimum length below which
// the answer is indeterminable. Conservative: "feasible" is always true, "infeasible" is always
// true, and feasible primitives may come back indeterminable.
#include "control/vehicle_parameters.h"
#include "planning/motion_primitive.h"

namespace aperture::planning {

struct FeasibilityLimits {
  double min_thrust_mps2 = 5.0;   // f_min, mass-normalised [m/s^2]; > 0 keeps the attitude defined
  double max_thrust_mps2 = 30.0;  // f_max [m/s^2]; ~3x hover, the thesis platforms
  double max_body_rate_radps = 10.0;  // omega_max on |omega_xy| [rad/s] (~570 deg/s)
  // Sections are never split below this length (the verdict is then indeterminable); 0.02 s is
  // the value of Mueller et al.'s published implementation. The recursion depth is at most
  // log2(T / min) and the work at most ~T / min section checks.
  double min_section_duration_s = 0.02;
  double gravity_mps2 = 9.81;

  // Thrust limits from the vehicle: f_min/max = 4 * rotor min/max thrust / mass (rotor fitness 1).
  static FeasibilityLimits FromVehicle(const control::VehicleParameters& vehicle,
                                       double max_body_rate_radps);
  // Throws std::invalid_argument naming the field if a limit is non-finite or inconsistent
  // (f_min < 0, f_max <= f_min, omega_max <= 0, min section <= 0, gravity <= 0).
  void Validate() const;
};

enum class Feasibility {
  kFeasible,              // every input stays within the limits over [0, T]
  kInfeasibleThrustHigh,  // some point provably needs f > f_max
  kInfeasibleThrustLow,   // some point provably needs f < f_min
  kIndeterminable,        // neither proven within the minimum section length
};

const char* ToString(Feasibility feasibility);

// The test over [0, T] of the primitive. Limits are not re-validated here (hot path): call
// FeasibilityLimits::Validate() once when the limits are built.
Feasibility CheckInputFeasibility(const MotionPrimitive& primitive,
                                  const FeasibilityLimits& limits);

// Linear position constraints (Mueller et al. 2015, Sec. on position feasibility; not in the
// project note): the minimum of <normal_W, p(t)> over [0, T], exact up to ~1e-15 relative. The
// projection is a quintic; its interior extrema are roots of the quartic <n, v(t)>, isolated
// through the chain of derivatives (each polynomial is monotone between the roots of its
// derivative) and refined by bisection. A floor at height h: MinimumProjection(p, z_W) >= h.
double MinimumProjection(const MotionPrimitive& primitive, const Eigen::Vector3d& normal_W);

}  // namespace aperture::planning
