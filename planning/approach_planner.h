#pragma once
// Perception-aware approach planning, Falanga et al. 2017 (seed 000) Sec. II-C to II-E.
// Candidates are minimum-jerk motion primitives (motion_primitive.h) from hover at a sampled start
// position to the start state of the traverse (p_0, v_0, a_0 = g_Pi), over a sampled duration.
// Each candidate is scored by (10), J = theta_rms / theta_bar + d_0 / d_bar, where theta is the
// smallest angle (9) between the camera's optical axis and the direction to the gap centre that a
// yaw rotation can achieve at each trajectory sample (8), and d_0 the distance from the start to
// the gap centre. The planner returns the lowest-cost candidate that passes the input-feasibility
// test (primitive_feasibility.h), keeps the gap within max_view_angle_rad at every sample and
// never gets nearer the gap than the traverse start (max_overshoot_m; beyond the paper).
// The approach ends with the traverse's thrust |<g, e3>| (traverse_trajectory.h): gaps whose short
// side is near horizontal need a near free-fall traverse, which f_min > 0 rightly rejects.
// Body rates are bounded for the position trajectory (omega_xy); the heading rate that the
// perception-aware yaw adds is not part of the feasibility test.
//
// Camera model of the yaw planning: the camera sits at the centre of mass (p_C = p; the lever arm
// of a few cm is negligible against metres to the gap), its optical axis is optical_axis_B in the
// body frame, and k = <optical axis, z_B> of (7) is its z_B component. Headings follow the
// TrajectoryPoint convention (x_B = y_C x z_B / |.|, Faessler thesis (F.9)-(F.11)).
#include <Eigen/Core>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <optional>

#include "control/trajectory_point.h"
#include "planning/motion_primitive.h"
#include "planning/primitive_feasibility.h"
#include "planning/traverse_trajectory.h"

namespace aperture::planning {

// (8): the unit optical axis r3* closest to d_W (camera to gap centre, W) with <r3*, z_B> = k.
// z_B_W must be a unit vector, |k| <= 1. When d_W is parallel to z_B every yaw is equally good and
// the result uses an arbitrary horizontal direction perpendicular to z_B.
Eigen::Vector3d OptimalOpticalAxis(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W,
                                   double k);
// (9): the angle between r3* and d_W [rad]; 0 for d_W = 0.
double MinimumViewAngle(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W, double k);
// Heading psi [rad] whose attitude (z_B_W, psi) turns optical_axis_B onto r3* of (8). Requires
// z_B_W.z() > 0 (upright thrust) and an optical axis not parallel to z_B.
double PerceptionAwareHeading(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W,
                              const Eigen::Vector3d& optical_axis_B);

// Where the approach must end and what it must look at.
struct ApproachTarget {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // traverse start p_0 (3a)
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // v_0 (3b)
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();  // g_Pi (5c)
  Eigen::Vector3d gap_center_W = Eigen::Vector3d::Zero();
  static ApproachTarget FromTraverse(const TraverseTrajectory& traverse);
};

struct ApproachPlannerParameters {
  // Start positions: a grid of start_counts points per axis over [offset_min, offset_max] in the
  // approach frame A at the traverse start: x_A backwards (horizontal projection of -v_0, or of
  // p_0 - gap centre when v_0 is vertical, or x_W), z_A up, y_A = z_A x x_A. A count of 1 uses
  // offset_min. Defaults span 1-4 m behind the traverse start, +-1.5 m sideways and +-1 m in
  // height.
  Eigen::Vector3d start_offset_min_A{1.0, -1.5, -1.0};
  Eigen::Vector3d start_offset_max_A{4.0, 1.5, 1.0};
  Eigen::Vector3i start_counts{7, 7, 5};
  // Durations: duration_count values evenly spaced over [duration_min_s, duration_max_s].
  double duration_min_s = 1.0;
  double duration_max_s = 4.0;
  int duration_count = 8;
  // Samples per candidate for theta_rms (including both ends).
  int samples_per_candidate = 20;
  // Normalisation constants of (10) (the paper tuned them by hand): 0.3 rad ~ 17 deg of view
  // angle weighs as much as 3 m of start distance.
  double view_angle_normalization_rad = 0.3;
  double start_distance_normalization_m = 3.0;
  // Candidates whose view angle (9) exceeds this at any sample lose the gap from the image and are
  // rejected; 80 deg keeps it inside a 180 deg fisheye with margin.
  double max_view_angle_rad = 1.396;
  Eigen::Vector3d optical_axis_B{1.0, 0.0, 0.0};  // forward-facing camera: k = 0 as in the paper
  // Floor: candidates whose height z_W drops below this anywhere (MinimumProjection, exact) are
  // rejected. -infinity (the default, since the floor height is scene knowledge) disables it.
  double min_height_m = -std::numeric_limits<double>::infinity();
  // Candidates that get nearer the gap than their end, the traverse start p_0, by more than this
  // (along p_0 -> gap centre; MinimumProjection, exact) are rejected: the approach never needs
  // to, and a replan from a state a disturbance pushed towards the gap would otherwise swing past
  // p_0 into the gap's frame and back (SITL, 5 m/s gusts). Keeping the previous primitive then
  // leaves the position controller to push back. >= 0.
  double max_overshoot_m = 0.05;
  FeasibilityLimits limits;
  // Throws std::invalid_argument naming the field for empty ranges, counts < 1, non-positive
  // durations/normalisations, an optical axis that is zero or parallel to z_B, or bad limits.
  void Validate() const;
};

struct ApproachCandidate {
  MotionPrimitive primitive;
  Feasibility feasibility = Feasibility::kIndeterminable;
  bool gap_in_view = false;         // view angle <= max_view_angle_rad at every sample
  bool above_floor = true;          // height >= min_height_m over [0, T]
  bool short_of_target = true;      // never nearer the gap than p_0 + max_overshoot_m
  double view_angle_rms_rad = 0.0;  // theta_rms
  double start_distance_m = 0.0;    // d_0
  double cost = 0.0;                // (10)
  bool IsValid() const {
    return feasibility == Feasibility::kFeasible && gap_in_view && above_floor &&
           short_of_target;
  }
};

struct ApproachPlan {
  std::optional<ApproachCandidate> best;  // empty when no candidate is valid
  int64_t candidates = 0;                 // grid size
  int64_t feasibility_tests = 0;          // candidates that could beat the best so far
  double solve_time_s = 0.0;
};
std::ostream& operator<<(std::ostream& os, const ApproachPlan& plan);

class ApproachPlanner {
 public:
  // Validates the parameters (see ApproachPlannerParameters::Validate).
  explicit ApproachPlanner(const ApproachPlannerParameters& parameters);
  const ApproachPlannerParameters& parameters() const { return parameters_; }

  // Grid accessors: start position (i, j, l) and duration index n.
  Eigen::Vector3d StartPosition(const ApproachTarget& target, int i, int j, int l) const;
  double Duration(int n) const;

  // Full evaluation of one candidate from hover (zero velocity and acceleration) at start_W.
  ApproachCandidate EvaluateCandidate(const ApproachTarget& target, const Eigen::Vector3d& start_W,
                                      double duration_s) const;
  // The lowest-cost valid candidate over the grid. Ties keep the first in (duration, x, y, z)
  // order. Candidates whose perception cost provably reaches the best so far (d_0 alone, or the
  // partial sum of theta^2) are abandoned before the rest of their samples and the feasibility
  // test, which does not change the result. No heap allocation in the loop. Throws
  // std::invalid_argument for a non-finite target.
  ApproachPlan Plan(const ApproachTarget& target) const;

  // Replanning during execution (Sec. II-C, V-A): the primitive from the current state to the
  // target over the remaining time, with its feasibility and view angles (the cost is filled in
  // but there is nothing to compare it with). The caller keeps the previous trajectory unless
  // IsValid() (Sec. V-A). Throws std::invalid_argument for remaining_s <= 0.
  ApproachCandidate Replan(const ApproachTarget& target, const Eigen::Vector3d& p_W,
                           const Eigen::Vector3d& v_W, const Eigen::Vector3d& a_W,
                           double remaining_s) const;

  // A reference sample of an approach primitive with the perception-aware heading of (8); heading
  // rate and acceleration by central differences (step 1 ms) of the unwrapped heading.
  control::TrajectoryPoint Sample(const MotionPrimitive& primitive,
                                  const Eigen::Vector3d& gap_center_W, double t_s) const;

 private:
  // theta samples and d_0 into candidate (perception part of (10)). Returns false, with the
  // candidate only partly scored, as soon as its cost provably reaches cost_bound; with an
  // infinite bound it always scores the whole candidate.
  bool ScorePerception(const MotionPrimitive& primitive, const Eigen::Vector3d& gap_center_W,
                       double cost_bound, ApproachCandidate& candidate) const;
  bool AboveFloor(const MotionPrimitive& primitive) const;
  bool ShortOfTarget(const MotionPrimitive& primitive, const ApproachTarget& target) const;
  double HeadingAt(const MotionPrimitive& primitive, const Eigen::Vector3d& gap_center_W,
                   double t_s) const;

  ApproachPlannerParameters parameters_;
  double axis_to_z_B_rad_ = 0.5 * 3.14159265358979323846;  // acos(k), k of (7)
};

}  // namespace aperture::planning
