#include "experiments/gap/gap_trial_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "control/attitude_controller.h"
#include "control/constants.h"

namespace aperture::experiments {
namespace {

using control::kNaN;
using control::kRadToDeg;

double WrapDeg(double angle_deg) {
  double wrapped = std::remainder(angle_deg, 360.0);
  if (wrapped <= -180.0) wrapped += 360.0;
  return wrapped;
}

std::string Format(const char* format, double a, double b = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), format, a, b);
  return buffer;
}

double HeightInGapFrame(const GapGeometry& gap, const Eigen::Vector3d& p_W) {
  return (gap.T_WG.inverse() * p_W).z();
}

// First ground-truth state violating the hover criteria in the final window, as a reason.
std::string CheckFinalHover(const std::vector<control::QuadState>& trajectory,
                            const GapGeometry& gap, const HoverCriteria& hover) {
  if (trajectory.empty() || trajectory.back().t_s < hover.window_s) {
    return "run shorter than the hover window";
  }
  const double t_from = trajectory.back().t_s - hover.window_s;
  for (auto it = trajectory.rbegin(); it != trajectory.rend() && it->t_s >= t_from; ++it) {
    const control::QuadState& s = *it;
    const double tilt_deg =
        std::acos(std::clamp((s.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)) * kRadToDeg;
    if (HeightInGapFrame(gap, s.p_WB) < 0.0) return "not past the gap at the end";
    if (s.v_W.norm() > hover.max_speed_mps) {
      return Format("not hovering at the end: speed %.2f m/s at t = %.2f s", s.v_W.norm(), s.t_s);
    }
    if (tilt_deg > hover.max_tilt_deg) {
      return Format("not hovering at the end: tilt %.1f deg at t = %.2f s", tilt_deg, s.t_s);
    }
    if (s.omega_B.head<2>().norm() > hover.max_rate_radps) {
      return Format("not hovering at the end: roll/pitch rate %.2f rad/s at t = %.2f s",
                    s.omega_B.head<2>().norm(), s.t_s);
    }
    if (s.p_WB.z() < hover.min_height_m) {
      return Format("not hovering at the end: height %.2f m at t = %.2f s", s.p_WB.z(), s.t_s);
    }
  }
  return {};
}

// a + s (b - a) for times, positions, velocities and rates; slerp for the attitude.
control::QuadState Interpolate(const control::QuadState& a, const control::QuadState& b, double s) {
  control::QuadState c;
  c.t_s = a.t_s + s * (b.t_s - a.t_s);
  c.p_WB = a.p_WB + s * (b.p_WB - a.p_WB);
  c.v_W = a.v_W + s * (b.v_W - a.v_W);
  c.q_WB = a.q_WB.slerp(s, b.q_WB);
  c.omega_B = a.omega_B + s * (b.omega_B - a.omega_B);
  return c;
}

}  // namespace

control::QuadState GroundTruthAt(const std::vector<control::QuadState>& trajectory, double t_s) {
  if (trajectory.empty()) throw std::invalid_argument("GroundTruthAt: empty trajectory");
  const auto later =
      std::lower_bound(trajectory.begin(), trajectory.end(), t_s,
                       [](const control::QuadState& s, double t) { return s.t_s < t; });
  if (later == trajectory.begin()) return trajectory.front();
  if (later == trajectory.end()) return trajectory.back();
  const control::QuadState& a = *(later - 1);
  const control::QuadState& b = *later;
  return Interpolate(a, b, (t_s - a.t_s) / (b.t_s - a.t_s));
}

Eigen::Isometry3d TrueGapMatchingEstimate(const Eigen::Isometry3d& T_WG_true,
                                          const Eigen::Matrix3d& R_WG_est) {
  // The pattern looks the same turned by 180 deg about z_G; the estimate's frame is the one of
  // the two whose x_G/y_G map the estimate's up (z_W of the mission frame) to the world's up.
  Eigen::Isometry3d T_WG = T_WG_true;
  if ((T_WG_true.linear() * R_WG_est.transpose())(2, 2) < 0.0) {
    T_WG.linear() = T_WG_true.linear() * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  }
  return T_WG;
}

std::optional<GapCrossing> FindGapCrossing(const std::vector<control::QuadState>& trajectory,
                                           const GapGeometry& gap) {
  if (!(gap.opening_m.array() > 0.0).all()) {
    throw std::invalid_argument("GapGeometry.opening_m must be positive (the inner rectangle)");
  }
  const Eigen::Isometry3d T_GW = gap.T_WG.inverse();
  for (std::size_t k = 1; k < trajectory.size(); ++k) {
    const control::QuadState& a = trajectory[k - 1];
    const control::QuadState& b = trajectory[k];
    const double z_a = (T_GW * a.p_WB).z();
    const double z_b = (T_GW * b.p_WB).z();
    if (!(z_a < 0.0 && z_b >= 0.0)) continue;
    const double s = z_a / (z_a - z_b);  // in (0, 1]
    GapCrossing crossing;
    crossing.t_s = a.t_s + s * (b.t_s - a.t_s);
    crossing.state = Interpolate(a, b, s);
    const control::QuadState& c = crossing.state;
    crossing.p_G_m = (T_GW * c.p_WB).head<2>();
    crossing.inside_opening =
        (crossing.p_G_m.cwiseAbs().array() < 0.5 * gap.opening_m.array()).all();
    return crossing;
  }
  return std::nullopt;
}

Eigen::Vector2d RollPitchDeg(const Eigen::Matrix3d& R_WB) {
  const double roll = std::atan2(R_WB(2, 1), R_WB(2, 2));
  const double pitch = -std::asin(std::clamp(R_WB(2, 0), -1.0, 1.0));
  return Eigen::Vector2d(roll, pitch) * kRadToDeg;
}

GapStateError ComputeErrorAtGap(const control::QuadState& actual,
                                const std::optional<GapCrossing>& crossing, const GapGeometry& gap,
                                const planning::TraverseTrajectory& plan,
                                double traverse_start_time_s) {
  // Estimated gap -> true gap: desired relative states keep their pose relative to the gap.
  Eigen::Isometry3d T_WG_est = Eigen::Isometry3d::Identity();
  T_WG_est.linear() = plan.gap().R_WG;
  T_WG_est.translation() = plan.gap().p_WG;
  const Eigen::Isometry3d T_true_est =
      TrueGapMatchingEstimate(gap.T_WG, T_WG_est.linear()) * T_WG_est.inverse();
  const double t_c = plan.time_to_gap_s();
  const Eigen::Matrix3d R_WB_plan =
      control::ComputeDesiredAttitude(plan.thrust_direction_W(), plan.heading_rad());

  GapStateError error;
  error.position_m = actual.p_WB - T_true_est * plan.Position(t_c);
  error.velocity_mps = actual.v_W - T_true_est.linear() * plan.Velocity(t_c);
  const Eigen::Vector2d roll_pitch = RollPitchDeg(actual.q_WB.toRotationMatrix());
  const Eigen::Vector2d desired = RollPitchDeg(T_true_est.linear() * R_WB_plan);
  error.orientation_deg =
      Eigen::Vector2d(WrapDeg(roll_pitch.x() - desired.x()), WrapDeg(roll_pitch.y() - desired.y()));
  error.time_s = crossing ? crossing->t_s - (traverse_start_time_s + t_c) : kNaN;
  return error;
}

GapTrialEvaluation EvaluateGapTrial(const sim::SitlResult& result, const GapGeometry& gap,
                                    const VehicleFootprint& footprint,
                                    const std::optional<planning::TraverseTrajectory>& plan,
                                    double traverse_start_time_s, const HoverCriteria& hover) {
  GapTrialEvaluation evaluation;
  evaluation.crossing = FindGapCrossing(result.trajectory, gap);
  evaluation.footprint_contact = FindFootprintContact(result.trajectory, gap, footprint);
  if (evaluation.crossing && plan) {
    evaluation.error = ComputeErrorAtGap(evaluation.crossing->state, evaluation.crossing, gap,
                                         *plan, traverse_start_time_s);
  }
  if (plan && std::isfinite(traverse_start_time_s) && !result.trajectory.empty()) {
    const double t_planned_s = traverse_start_time_s + plan->time_to_gap_s();
    evaluation.error_at_planned_tc =
        ComputeErrorAtGap(GroundTruthAt(result.trajectory, t_planned_s), evaluation.crossing, gap,
                          *plan, traverse_start_time_s);
  }
  // The first failed criterion, in the order things happen in a flight. A plan is needed for
  // the errors, not for success.
  if (result.outcome == sim::SitlResult::Outcome::kCollision) {
    evaluation.failure_reason = result.reason.empty() ? "collision" : result.reason;
  } else if (evaluation.crossing && !evaluation.crossing->inside_opening) {
    evaluation.failure_reason =
        Format("crossed the gap plane outside the opening at x_G = %.3f m, y_G = %.3f m",
               evaluation.crossing->p_G_m.x(), evaluation.crossing->p_G_m.y());
  } else if (const std::optional<FootprintContact>& contact = evaluation.footprint_contact) {
    evaluation.failure_reason =
        "footprint: " + contact->part + " meets the gap panel at x_G = " +
        Format("%.3f m, y_G = %.3f m", contact->p_G_m.x(), contact->p_G_m.y()) +
        Format(" (t = %.3f s)", contact->t_s);
  } else if (!evaluation.crossing) {
    evaluation.failure_reason =
        plan ? "never crossed the gap plane" : "never crossed the gap plane (no traverse plan)";
  } else {
    evaluation.failure_reason = CheckFinalHover(result.trajectory, gap, hover);
  }
  evaluation.success = evaluation.failure_reason.empty();
  return evaluation;
}

}  // namespace aperture::experiments
