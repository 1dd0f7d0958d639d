#pragma once
// Ground-truth evaluation of one gap flight (seed 000 Sec. IV-B): success and the Table I errors.
//
// Success (the paper's definition): the vehicle passed through the gap without collision and
// recovered to a stable hover. Here: the run has no collision, the ground truth crosses the gap
// plane for the first time with B's origin inside the opening (inner rectangle of the pattern),
// the vehicle's footprint (body sphere, propeller disks, arms; gap_footprint.h) never meets the
// panel, and over the final hover window the vehicle is past the gap plane, slow, level and not
// rotating (the position lock after the traverse).
//
// Errors at the gap, actual minus desired state, each relative to its own gap. Desired = the
// traverse plan at its t_c (the gap centre of its apex, eqs. (3)-(5)) relative to the plan's gap
// estimate (p_WG, R_WG of planning::GapPose, possibly wrong); actual = the ground truth relative
// to the true gap. Both relative states are mapped onto the true gap (desired_W = T_WG_true *
// T_WG_est^-1 * desired), so the error is in world axes, as the paper's motion capture measured:
//   position_m    = p_true - T_WG_true T_WG_est^-1 p_plan(t_c)
//   velocity_mps  = v_true - R_WG_true R_WG_est^T v_plan(t_c)
//   orientation   = [roll, pitch](R_WB_true) - [roll, pitch](R_WG_true R_WG_est^T R_WB_plan),
//                   ZYX Euler angles (R = Rz Ry Rx) in degrees, wrapped to (-180, 180]; R_WB_plan
//                   has z_B along the plan's thrust direction (1) and x_B at its heading.
//   time_s        = t_cross - (traverse start + plan t_c): arrival late (> 0) or early (< 0).
// Two instants for "true" (issue 21, item 4):
//   * Table I (the paper's definition): the ground truth at the planned t_c (traverse start +
//     plan t_c), for every trial with a plan, crossed or not (error_at_planned_tc);
//   * at the crossing: the ground truth when it crosses the gap plane (error), which removes the
//     along-track and timing error (x ~ 0 on unpitched gaps by construction).
// A perfect estimate makes T_WG_true T_WG_est^-1 the identity (the usual definition); a wrong
// gap estimate shows up here only through the flown path, as it would in the real system.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "experiments/gap/gap_footprint.h"
#include "experiments/gap/gap_geometry.h"
#include "planning/traverse_trajectory.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

struct GapCrossing {
  double t_s = 0.0;
  control::QuadState state;  // ground truth interpolated to t_s (linear; slerp for attitude)
  Eigen::Vector2d p_G_m = Eigen::Vector2d::Zero();  // where B's origin crossed (x_G, y_G) [m]
  bool inside_opening = false;
};

// First crossing of the gap plane from its approach side (z_G < 0) to z_G >= 0 between two
// consecutive ground-truth states; nullopt if it never happens. Throws std::invalid_argument if
// the opening is not positive.
std::optional<GapCrossing> FindGapCrossing(const std::vector<control::QuadState>& trajectory,
                                           const GapGeometry& gap);

struct GapStateError {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector2d orientation_deg = Eigen::Vector2d::Zero();  // [roll, pitch]
  double time_s = 0.0;
};

// The error at the gap defined in the header comment of `actual` (the ground truth at the
// crossing or at the planned t_c); time_s from `crossing` (NaN without one);
// `traverse_start_time_s` is the simulator time the plan's t = 0 was flown from (NaN gives a NaN
// time_s).
GapStateError ComputeErrorAtGap(const control::QuadState& actual,
                                const std::optional<GapCrossing>& crossing, const GapGeometry& gap,
                                const planning::TraverseTrajectory& plan,
                                double traverse_start_time_s);

// Ground truth at t_s, interpolated between the recorded states as at the crossing (linear,
// slerp for the attitude), clamped to the recorded span. Throws for an empty trajectory.
control::QuadState GroundTruthAt(const std::vector<control::QuadState>& trajectory, double t_s);

// The true gap pose in the one of the pattern's two look-alike frames (turned by 180 deg about
// z_G) whose up matches the estimate R_WG_est's (the error at the gap compares relative states
// through it).
Eigen::Isometry3d TrueGapMatchingEstimate(const Eigen::Isometry3d& T_WG_true,
                                          const Eigen::Matrix3d& R_WG_est);

// Roll and pitch [deg] of R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Vector2d RollPitchDeg(const Eigen::Matrix3d& R_WB);

// A stable hover at the end of the run.
struct HoverCriteria {
  double window_s = 0.5;       // the final part of the run that must hover [s]
  double max_speed_mps = 0.3;  // |v| in the window
  double max_tilt_deg = 10.0;  // angle between z_B and z_W in the window
  // Roll/pitch rate |omega_xy| in the window: a hover may turn about z_B (a heading hold does)
  // without losing its stability.
  double max_rate_radps = 0.5;
  double min_height_m = 0.2;  // z_W of B in the window (not sitting on the ground)
};

struct GapTrialEvaluation {
  bool success = false;
  // Empty on success; else the first failed criterion, e.g. "collision: body with 'gap'",
  // "crossed the gap plane outside the opening at x_G = 0.45 m, y_G = -0.02 m",
  // "never crossed the gap plane", "not hovering at the end: speed 1.2 m/s at t = 9.50 s".
  std::string failure_reason;
  std::optional<GapCrossing> crossing;
  std::optional<GapStateError> error;  // at the crossing, when crossed with a plan
  // Table I: at the planned t_c, when a plan was flown (traverse start finite), crossed or not.
  std::optional<GapStateError> error_at_planned_tc;
  std::optional<FootprintContact> footprint_contact;  // the first, if the footprint met the panel
};

// Evaluates a finished run of a vehicle with `footprint`. `plan` is the autopilot's traverse plan
// (nullopt if it never planned one). Success also needs the run to last the hover window (a run
// shorter than it fails).
GapTrialEvaluation EvaluateGapTrial(const sim::SitlResult& result, const GapGeometry& gap,
                                    const VehicleFootprint& footprint,
                                    const std::optional<planning::TraverseTrajectory>& plan,
                                    double traverse_start_time_s, const HoverCriteria& hover = {});

}  // namespace aperture::experiments
