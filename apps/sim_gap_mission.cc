#include "apps/sim_gap_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "experiments/gap/gap_mission_factory.h"
#include "planning/gap_mission/gap_mission_params_io.h"

namespace aperture::apps {
namespace {

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

struct Crossing {
  double t_s = 0.0;
  control::QuadState state;                     // linear interpolation (attitude: slerp)
  Eigen::Vector3d p_G = Eigen::Vector3d::Zero();  // B's origin in the true gap frame
};

// First crossing of z_G = 0 from z_G < 0 between consecutive ground-truth states.
std::optional<Crossing> FindCrossing(const std::vector<control::QuadState>& trajectory,
                                     const Eigen::Isometry3d& T_GW) {
  for (std::size_t k = 1; k < trajectory.size(); ++k) {
    const control::QuadState& a = trajectory[k - 1];
    const control::QuadState& b = trajectory[k];
    const double za = (T_GW * a.p_WB).z(), zb = (T_GW * b.p_WB).z();
    if (!(za < 0.0 && zb >= 0.0)) continue;
    const double s = -za / (zb - za);
    Crossing crossing;
    crossing.t_s = a.t_s + s * (b.t_s - a.t_s);
    crossing.state.t_s = crossing.t_s;
    crossing.state.p_WB = a.p_WB + s * (b.p_WB - a.p_WB);
    crossing.state.v_W = a.v_W + s * (b.v_W - a.v_W);
    crossing.state.q_WB = a.q_WB.slerp(s, b.q_WB);
    crossing.p_G = T_GW * crossing.state.p_WB;
    return crossing;
  }
  return std::nullopt;
}

// Ground truth nearest to t_s (the trajectory is recorded at every few ms).
control::QuadState StateAt(const std::vector<control::QuadState>& trajectory, double t_s) {
  const auto later = std::lower_bound(
      trajectory.begin(), trajectory.end(), t_s,
      [](const control::QuadState& s, double t) { return s.t_s < t; });
  return later == trajectory.end() ? trajectory.back() : *later;
}

}  // namespace

SimGapMission::SimGapMission(const sim::Scenario& scenario, const sim::SitlRunnerParams& params,
                             config::ParamReader& mission_config)
    : params_(experiments::GapMissionParamsFor(scenario, params.imu)) {
  LoadParams(mission_config, &params_);
  mission_ = experiments::MakeGapMission(scenario, params.dynamics.vehicle, params_);
}

void SimGapMission::DrawOverlay(cv::Mat* onboard_bgr) const {
  const perception::GapDetection& detection = mission_->last_detection();
  if (!detection.detected() || detection.corners_px.size() != 8) return;
  const cv::Scalar colors[2] = {cv::Scalar(0, 0, 255), cv::Scalar(0, 255, 0)};  // outer, inner
  for (int quad = 0; quad < 2; ++quad) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d& a = detection.corners_px[4 * quad + k];
      const Eigen::Vector2d& b = detection.corners_px[4 * quad + (k + 1) % 4];
      cv::line(*onboard_bgr, cv::Point2d(a.x(), a.y()), cv::Point2d(b.x(), b.y()), colors[quad], 1,
               cv::LINE_AA);
    }
  }
}

nlohmann::json SimGapMission::Summary(const sim::SitlResult& result,
                                      const sim::Scenario& scenario) const {
  const planning::GapMission& m = *mission_;
  nlohmann::json summary;
  summary["phase"] = planning::ToString(m.phase());
  summary["status"] = m.status();
  if (!m.reason().empty()) summary["abort_reason"] = m.reason();
  nlohmann::json phases = nlohmann::json::array();
  for (const planning::GapMissionPhaseChange& change : m.phase_changes()) {
    phases.push_back({{"phase", planning::ToString(change.phase)}, {"t_s", change.t_s}});
  }
  summary["phase_starts"] = phases;
  summary["frames_processed"] = m.frames_processed();
  summary["detections"] = m.detections();
  summary["pose_updates_rejected"] = m.updates_rejected();
  summary["filter_restarts"] = m.filter_restarts();
  summary["approach_fallback_limits"] = m.used_fallback_limits();
  summary["replans_accepted"] = m.replans_accepted();
  summary["replans_kept_previous"] = m.replans_rejected();

  // Ground truth: the scene's gap, flipped by 180 deg about z_G if needed so that it is the one
  // of the pattern's symmetric frames the mission's estimate refers to (mission z_W maps up).
  Eigen::Isometry3d T_WG_true = scenario.scene().object("gap").T_WO;
  const Eigen::Matrix3d R_WG_est = m.gap_W().R_WG;
  if ((T_WG_true.linear() * R_WG_est.transpose())(2, 2) < 0.0) {
    T_WG_true.linear() = T_WG_true.linear() * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  }
  const std::optional<Crossing> crossing = FindCrossing(result.trajectory, T_WG_true.inverse());
  const sim::GapParams& gap = scenario.params().gap;
  const bool inside = crossing && std::abs(crossing->p_G.x()) < 0.5 * gap.opening_m.x() &&
                      std::abs(crossing->p_G.y()) < 0.5 * gap.opening_m.y();
  // A collision after the crossing (e.g. during the recovery) still fails the flight.
  summary["passed"] = crossing.has_value() && inside && !result.collision.has_value();
  summary["crossed_gap_plane"] = crossing.has_value();
  if (crossing) {
    summary["crossing"] = {{"t_s", crossing->t_s},
                           {"p_G_m", {crossing->p_G.x(), crossing->p_G.y()}},
                           {"inside_opening", inside},
                           {"speed_mps", crossing->state.v_W.norm()}};
  }
  if (const std::optional<planning::TraverseTrajectory>& plan = m.traverse_plan()) {
    const double t_c = plan->time_to_gap_s();
    summary["traverse"] = {{"start_time_s", m.traverse_start_time_s()},
                           {"time_to_gap_s", t_c},
                           {"duration_s", plan->duration_s()},
                           {"d_m", plan->d_m()},
                           {"l_m", plan->l_m()},
                           {"start_speed_mps", plan->start_velocity_W().norm()},
                           {"collective_thrust_mps2", plan->collective_thrust_mps2()}};
    if (crossing && std::isfinite(m.traverse_start_time_s())) {
      // Plan in W through the true gap: T_WG_true * T_WG_est^-1 (mission frame -> W).
      Eigen::Isometry3d T_WG_est = Eigen::Isometry3d::Identity();
      T_WG_est.linear() = R_WG_est;
      T_WG_est.translation() = m.gap_W().p_WG;
      const Eigen::Isometry3d T_W_mission = T_WG_true * T_WG_est.inverse();
      const Eigen::Vector3d p_plan_W = T_W_mission * plan->Position(t_c);
      const Eigen::Vector3d v_plan_W = T_W_mission.linear() * plan->Velocity(t_c);
      // The traverse start split into estimation and tracking errors (mission frame): the true
      // state then vs the estimate, and vs the plan's start state (3a), (3b).
      const control::QuadState truth = StateAt(result.trajectory, m.traverse_start_time_s());
      const Eigen::Isometry3d T_mission_W = T_W_mission.inverse();
      const Eigen::Vector3d p_true = T_mission_W * truth.p_WB;
      const Eigen::Vector3d v_true = T_mission_W.linear() * truth.v_W;
      const control::QuadState& estimate = *m.traverse_start_estimate();
      summary["traverse_start"] = {
          {"estimate_error_position_m", Vec(estimate.p_WB - p_true)},
          {"estimate_error_velocity_mps", Vec(estimate.v_W - v_true)},
          {"tracking_error_position_m", Vec(p_true - plan->start_position_W())},
          {"tracking_error_velocity_mps", Vec(v_true - plan->start_velocity_W())}};
      summary["error_at_gap"] = {
          {"position_m", Vec(crossing->state.p_WB - p_plan_W)},
          {"velocity_mps", Vec(crossing->state.v_W - v_plan_W)},
          {"time_s", crossing->t_s - (m.traverse_start_time_s() + t_c)}};
    }
  }
  return summary;
}

std::string SimGapMission::OutcomeLine(const nlohmann::json& summary) const {
  std::string line = std::string("gap mission: ") +
                     (summary.value("passed", false) ? "passed the gap" : "did NOT pass the gap") +
                     ", phase " + summary.value("phase", std::string("?"));
  if (summary.contains("error_at_gap")) {
    const nlohmann::json& p = summary["error_at_gap"]["position_m"];
    char buffer[96];
    std::snprintf(buffer, sizeof(buffer), ", position error at the gap [%.3f %.3f %.3f] m",
                  p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    line += buffer;
  }
  return line;
}

}  // namespace aperture::apps
