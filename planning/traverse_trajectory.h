#pragma once
// Traverse trajectory through a narrow gap, Falanga et al. 2017 (seed 000) Sec. II-A/B, eqs.
// (1)-(6). The vehicle flies a constant-acceleration arc in the plane Pi orthogonal to the gap,
// through the gap centre and parallel to its long side: a thrust of magnitude |<g, e3>| along e3
// cancels gravity normal to Pi (1), leaving the in-plane acceleration g_Pi (2), (5).
//
// Gap frame G (input convention): p_WG is the gap centre; columns of R_WG are x_G along the long
// side, y_G along the short side, z_G normal to the gap pointing in the direction of traversal.
// Plane basis: e2 = z_G (orthogonal to the gap), e3 = +-y_G (normal of Pi), e1 = e2 x e3 (along
// the long side); the sign of e3 is chosen so that g_Pi,1 = <g, e1> <= 0, which (4) requires.
//
// Parameterisation: the paper's (d, l) with t_c = sqrt(-2 l / g_Pi,1) (4), equivalently
// l = -g_Pi,1 t_c^2 / 2. The optimiser works on (d, t_c), a bijection for g_Pi,1 < 0 that stays
// defined when the long side is horizontal (g_Pi,1 = 0, then l = 0). With (4), (3b) gives
// v_0,1 = -g_Pi,1 t_c: the gap centre is the apex of the arc along e1.
//
// The case g_Pi,2 < 0 (e2 points upward, the paper omits it): along e2 the vehicle decelerates,
// p_2(t) is a concave parabola, and it may cross the gap plane p_2 = d before t_c (away from the
// gap centre) unless v_2(t_c) = d / t_c + g_Pi,2 t_c / 2 >= 0; to also cover the distance d past
// the gap that the traverse ends with (equal distances before and after the gap along e2), it
// needs v_2(t_c)^2 >= 2 |g_Pi,2| d. Both hold iff  v_2(t_c) >= sqrt(2 |g_Pi,2| d),  which the
// optimisation adds as a constraint when g_Pi,2 < 0 (for g_Pi,2 >= 0 both hold automatically).
//
// The traverse lasts from t = 0 (start, p_0, v_0) through t_c (gap centre) to duration_s, when
// p_2 = 2 d. Time t is relative to the start of the traverse.
#include <Eigen/Core>
#include <iosfwd>
#include <optional>

#include "control/trajectory_point.h"

namespace aperture::planning {

struct GapPose {
  Eigen::Vector3d p_WG = Eigen::Vector3d::Zero();      // gap centre in W [m]
  Eigen::Matrix3d R_WG = Eigen::Matrix3d::Identity();  // see the header comment for the axes
};

struct TraverseParameters {
  double max_start_speed_mps = 3.0;    // v_0,max of (6); the paper's experiments (Sec. IV-A)
  double min_start_distance_m = 0.25;  // d_min of (6); the paper's value (printed "0.25 cm")
  // Upper bounds that keep the search box finite; far above any optimum for these limits.
  double max_start_distance_m = 5.0;
  double max_time_to_gap_s = 3.0;
  double gravity_mps2 = 9.81;
  double relative_tolerance = 1e-10;  // NLopt xtol_rel on (d, t_c)
  int max_evaluations = 500;
  // Throws std::invalid_argument naming the field if a value is non-finite or out of range.
  void Validate() const;
};

class TraverseTrajectory {
 public:
  // The trajectory (3)-(5) for start distance d_m along e2 and time to the gap centre
  // time_to_gap_s (l follows from (4)). Throws std::invalid_argument if d_m or time_to_gap_s is
  // not positive and finite, R_WG is not a rotation, or gravity_mps2 <= 0.
  TraverseTrajectory(const GapPose& gap, double d_m, double time_to_gap_s, double gravity_mps2);

  const GapPose& gap() const { return gap_; }
  const Eigen::Vector3d& e1_W() const { return e1_W_; }
  const Eigen::Vector3d& e2_W() const { return e2_W_; }
  const Eigen::Vector3d& e3_W() const { return e3_W_; }
  // g_Pi of (1) in W and its components along e1, e2.
  const Eigen::Vector3d& plane_gravity_W() const { return plane_gravity_W_; }
  double plane_gravity_1() const { return g1_; }
  double plane_gravity_2() const { return g2_; }
  double d_m() const { return d_m_; }
  double l_m() const { return l_m_; }
  double time_to_gap_s() const { return time_to_gap_s_; }            // t_c
  double duration_s() const { return duration_s_; }                  // until p_2 = 2 d
  const Eigen::Vector3d& start_position_W() const { return p0_W_; }  // (3a)
  const Eigen::Vector3d& start_velocity_W() const { return v0_W_; }  // (3b)
  // Mass-normalised collective thrust |<g, e3>| [m/s^2] along thrust_direction_W() (= +-e3).
  double collective_thrust_mps2() const { return thrust_mps2_; }
  const Eigen::Vector3d& thrust_direction_W() const { return thrust_direction_W_; }
  // Heading of the traverse: x_B from the start towards the gap centre (in Pi), which is where a
  // forward camera looks at the end of a perception-aware approach (approach_planner.h).
  double heading_rad() const { return heading_rad_; }

  Eigen::Vector3d Position(double t_s) const;  // (5a)
  Eigen::Vector3d Velocity(double t_s) const;  // (5b)
  // (5a)-(5c) with zero jerk and snap, constant heading.
  control::TrajectoryPoint Sample(double t_s) const;

 private:
  GapPose gap_;
  Eigen::Vector3d e1_W_, e2_W_, e3_W_, plane_gravity_W_, p0_W_, v0_W_, thrust_direction_W_;
  double g1_ = 0.0, g2_ = 0.0, d_m_ = 0.0, l_m_ = 0.0, time_to_gap_s_ = 0.0, duration_s_ = 0.0;
  double thrust_mps2_ = 0.0, heading_rad_ = 0.0;
};

struct TraverseOptimizationResult {
  enum class Status {
    kSuccess,        // SLSQP converged and every constraint of (6) holds at the solution
    kInfeasible,     // the returned point violates a constraint (no feasible (d, t_c) found)
    kSolverFailure,  // NLopt reported an error
  };
  Status status = Status::kSolverFailure;
  int iterations = 0;  // objective evaluations
  double cost = 0.0;   // t_c [s]
  double solve_time_s = 0.0;
  double max_constraint_violation = 0.0;         // of the scaled constraints at the returned point
  std::optional<TraverseTrajectory> trajectory;  // set unless kSolverFailure
};

std::ostream& operator<<(std::ostream& os, const TraverseOptimizationResult& result);

// Problem (6): min t_c over (d, t_c) s.t. |v_0| <= v_0,max, d >= d_min (+ the g_Pi,2 < 0
// constraint above), solved with NLopt SLSQP (LD_SLSQP) and analytic gradients.
TraverseOptimizationResult OptimizeTraverseTrajectory(const GapPose& gap,
                                                      const TraverseParameters& parameters);

}  // namespace aperture::planning
