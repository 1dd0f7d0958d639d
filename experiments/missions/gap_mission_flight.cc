#include "experiments/missions/gap_mission_flight.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "config/yaml_write_archive.h"
#include "experiments/gap/gap_mission_factory.h"
#include "experiments/gap/gap_trial_evaluation.h"
#include "experiments/gap/gap_trial_record_json.h"
#include "experiments/missions/odometry_adapter.h"
#include "output/json_eigen.h"
#include "planning/gap_mission/gap_mission_params_io.h"

namespace aperture::experiments {
namespace {

class GapMissionFlight final : public MissionFlight {
 public:
  explicit GapMissionFlight(const MissionContext& context)
      : scenario_(context.scenario),
        params_(GapMissionParamsFor(context.scenario, context.sitl.imu)),
        odometry_(LoadOdometryParams(context, kGapOdometrySalt)),
        footprint_(VehicleFootprintOf(context.sitl.dynamics.vehicle, context.sitl.collision)) {
    LoadParams(context.params, &params_);  // config::LoadParams: reads, rejects, validates
    mission_ = MakeGapMission(context.scenario, context.sitl.dynamics.vehicle, params_);
    adapter_ = MakeOdometryAdapter(mission_.get(), odometry_);
  }

  perception::Autopilot& autopilot() override { return *adapter_; }
  YAML::Node EffectiveParams() const override {
    YAML::Node node = config::DumpParams(params_);
    node["odometry"] = config::DumpParams(odometry_);
    return node;
  }
  void DrawOverlay(cv::Mat& onboard_bgr) const override { mission_->DrawOverlay(onboard_bgr); }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    const planning::GapMission& m = *mission_;
    const GapGeometry gap = GapGeometryOf(scenario_);
    const GapTrialEvaluation evaluation =
        EvaluateGapTrial(result, gap, footprint_, m.traverse_plan(), m.traverse_start_time_s());

    MissionEvaluation out;
    out.passed = evaluation.success;
    nlohmann::json& figures = out.figures;
    figures["phase"] = planning::ToString(m.phase());
    figures["status"] = m.status();
    if (!m.reason().empty()) figures["abort_reason"] = m.reason();
    if (!evaluation.success) figures["failure_reason"] = evaluation.failure_reason;
    nlohmann::json phases = nlohmann::json::array();
    for (const planning::GapMissionPhaseChange& change : m.phase_changes()) {
      phases.push_back({{"phase", planning::ToString(change.phase)}, {"t_s", change.t_s}});
    }
    figures["phase_starts"] = phases;
    figures["frames_processed"] = m.frames_processed();
    figures["detections"] = m.detections();
    figures["pose_updates_rejected"] = m.updates_rejected();
    figures["filter_restarts"] = m.filter_restarts();
    figures["filter_restarts_refused"] = m.filter_restarts_refused();
    figures["recovery_odometry_fused"] = m.odometry_poses_fused();
    figures["recovery_range_heights_fused"] = m.fusion_counts().heights_applied;
    figures["recovery_range_heights_rejected"] = m.fusion_counts().heights_rejected;
    figures["approach_fallback_limits"] = m.used_fallback_limits();
    figures["replans_accepted"] = m.replans_accepted();
    figures["replans_kept_previous"] = m.replans_rejected();
    figures["crossed_gap_plane"] = evaluation.crossing.has_value();
    if (const std::optional<GapCrossing>& crossing = evaluation.crossing) {
      figures["crossing"] = {{"t_s", crossing->t_s},
                             {"p_G_m", output::EigenToJson(crossing->p_G_m)},
                             {"inside_opening", crossing->inside_opening},
                             {"speed_mps", crossing->state.v_W.norm()}};
    }
    if (evaluation.error) figures["error_at_gap"] = GapStateErrorToJson(*evaluation.error);
    if (evaluation.error_at_planned_tc) {
      figures["error_at_planned_tc"] = GapStateErrorToJson(*evaluation.error_at_planned_tc);
    }
    if (const std::optional<planning::TraverseTrajectory>& plan = m.traverse_plan()) {
      figures["traverse"] = {{"start_time_s", m.traverse_start_time_s()},
                             {"time_to_gap_s", plan->time_to_gap_s()},
                             {"duration_s", plan->duration_s()},
                             {"d_m", plan->d_m()},
                             {"l_m", plan->l_m()},
                             {"start_speed_mps", plan->start_velocity_W().norm()},
                             {"collective_thrust_mps2", plan->collective_thrust_mps2()}};
      if (std::isfinite(m.traverse_start_time_s()) && !result.trajectory.empty()) {
        figures["traverse_start"] = TraverseStartErrors(result, gap, *plan);
      }
    }
    char line[200];
    if (evaluation.error) {
      const Eigen::Vector3d& p = evaluation.error->position_m;
      std::snprintf(line, sizeof(line), ", position error at the gap [%.3f %.3f %.3f] m", p.x(),
                    p.y(), p.z());
    } else {
      line[0] = '\0';
    }
    out.outcome = std::string("gap mission: ") +
                  (out.passed ? "passed the gap"
                              : "did NOT pass the gap (" + evaluation.failure_reason + ")") +
                  ", phase " + planning::ToString(m.phase()) + line;
    return out;
  }

 private:
  // The traverse start split into estimation and tracking errors, in the mission frame: the
  // true state then vs the estimate, and vs the plan's start state (3a), (3b).
  nlohmann::json TraverseStartErrors(const sim::SitlResult& result, const GapGeometry& gap,
                                     const planning::TraverseTrajectory& plan) const {
    const planning::GapMission& m = *mission_;
    Eigen::Isometry3d T_WG_est = Eigen::Isometry3d::Identity();
    T_WG_est.linear() = m.gap_W().R_WG;
    T_WG_est.translation() = m.gap_W().p_WG;
    const Eigen::Isometry3d T_mission_W =
        (TrueGapMatchingEstimate(gap.T_WG, T_WG_est.linear()) * T_WG_est.inverse()).inverse();
    const control::QuadState truth = GroundTruthAt(result.trajectory, m.traverse_start_time_s());
    const Eigen::Vector3d p_true = T_mission_W * truth.p_WB;
    const Eigen::Vector3d v_true = T_mission_W.linear() * truth.v_W;
    const control::QuadState& estimate = *m.traverse_start_estimate();
    return {{"estimate_error_position_m", output::EigenToJson(estimate.p_WB - p_true)},
            {"estimate_error_velocity_mps", output::EigenToJson(estimate.v_W - v_true)},
            {"tracking_error_position_m", output::EigenToJson(p_true - plan.start_position_W())},
            {"tracking_error_velocity_mps", output::EigenToJson(v_true - plan.start_velocity_W())}};
  }

  const sim::Scenario& scenario_;
  planning::GapMissionParams params_;
  sim::OdometrySensorParams odometry_;  // the recovery's visual odometry (SVO in [12])
  VehicleFootprint footprint_;          // the SITL collision geometry, for the footprint check
  std::unique_ptr<planning::GapMission> mission_;
  std::unique_ptr<OdometryAdapter> adapter_;
};

}  // namespace

std::unique_ptr<MissionFlight> MakeGapMissionFlight(const MissionContext& context) {
  return std::make_unique<GapMissionFlight>(context);
}

}  // namespace aperture::experiments
