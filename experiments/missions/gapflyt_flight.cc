#include "experiments/missions/gapflyt_flight.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "experiments/gap/gap_mission_factory.h"
#include "experiments/gap/gap_trial_evaluation.h"
#include "experiments/gapflyt/gapflyt_evaluation.h"
#include "output/json_eigen.h"
#include "output/svg_plot.h"
#include "planning/gapflyt/gapflyt_mission.h"
#include "planning/gapflyt/gapflyt_mission_params_io.h"

namespace aperture::experiments {
namespace {

class GapflytFlight final : public MissionFlight {
 public:
  explicit GapflytFlight(const MissionContext& context)
      : scenario_(context.scenario),
        vehicle_(context.sitl.dynamics.vehicle),
        collision_(context.sitl.collision) {
    planning::GapflytMissionParams params;
    params.camera_id = ForwardCameraIndex(context.scenario, "gapflyt");
    const sim::ScenarioCamera& camera = context.scenario.cameras()[params.camera_id];
    params.camera_rate_hz = camera.rate_hz;
    planning::LoadParams(context.params, &params);
    camera_ = camera.model;
    T_BC_ = *camera.T_BC;
    mission_ =
        std::make_unique<planning::GapflytMission>(params, camera.model, *camera.T_BC, vehicle_);
  }

  perception::Autopilot& autopilot() override { return *mission_; }
  void DrawOverlay(cv::Mat& onboard_bgr) const override { mission_->DrawOverlay(onboard_bgr); }

  void AddReportSections(const MissionEvaluation& /*evaluation*/, const sim::SitlResult& /*result*/,
                         output::HtmlReport* report) const override {
    const std::vector<planning::GapflytServoSample>& trace = mission_->servo_trace();
    if (trace.empty()) return;
    std::vector<double> t, error, vx, vy, vz;
    for (const planning::GapflytServoSample& s : trace) {
      t.push_back(s.t_s);
      error.push_back(s.error_norm);
      vx.push_back(s.v_B.x());
      vy.push_back(s.v_B.y());
      vz.push_back(s.v_B.z());
    }
    const std::string law = servo::ToString(mission_->law());
    report->AddSection("GapFlyt servo (" + law + ")");
    output::SvgPlot error_plot({"Servo feature error |s - s*|", "t [s]", "error"});
    error_plot.AddLine(law, t, error);
    report->AddSvg(error_plot.Render(),
                   law == "pid" ? "Safe-point error e = x_s - x_B (normalized image units)"
                                : "Moment features [x_n, y_n, a_n] to the commit view");
    output::SvgPlot velocity_plot({"Body velocity reference", "t [s]", "v_B [m/s]"});
    velocity_plot.AddLine("forward x_B", t, vx).AddLine("left y_B", t, vy).AddLine("up z_B", t, vz);
    report->AddSvg(velocity_plot.Render(), "The servo's reference to the position controller");
  }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    const planning::GapflytMission& m = *mission_;
    const GapflytOpening opening = OpeningFromScene(scenario_.scene());
    const GapflytEvaluation evaluation =
        EvaluateGapflytFlight(result, opening, vehicle_, collision_);
    MissionEvaluation out;
    out.passed = evaluation.passed;
    nlohmann::json& f = out.figures;
    f["law"] = servo::ToString(m.law());
    f["phase"] = planning::ToString(m.phase());
    f["status"] = m.status();
    f["reason"] = m.reason();
    nlohmann::json phases = nlohmann::json::array();
    for (const planning::GapflytPhaseChange& change : m.phase_changes()) {
      phases.push_back({{"phase", planning::ToString(change.phase)}, {"t_s", change.t_s}});
    }
    f["phase_starts"] = phases;
    f["scans"] = m.scans();
    f["scan_statuses"] = m.scan_statuses();
    f["frames_tracked"] = m.frames_tracked();
    if (m.detection() && !result.trajectory.empty()) {
      const control::QuadState truth = GroundTruthAt(result.trajectory, m.detection_t_s());
      Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
      T_WB.linear() = truth.q_WB.toRotationMatrix();
      T_WB.translation() = truth.p_WB;
      nlohmann::json detection = {{"t_s", m.detection_t_s()}};
      try {
        const perception::OpeningScore score =
            ScoreGapflytDetection(m.detection()->opening, opening, *camera_, T_WB * T_BC_);
        detection["overlap"] = score.overlap;
        detection["false_negative"] = score.false_negative;
        detection["false_positive"] = score.false_positive;
        detection["detected"] = score.detected();
      } catch (const std::invalid_argument& e) {
        detection["detected"] = false;
        detection["score_error"] = e.what();
      }
      f["detection"] = detection;
    }
    if (const std::optional<Eigen::Vector3d>& offset_B = m.commit_aim_offset_B()) {
      f["commit_aim_offset_m"] = offset_B->norm();  // before the cap max_aim_correction_m
    }
    f["crossed"] = evaluation.crossing.has_value();
    if (!evaluation.passed) f["failure_reason"] = evaluation.failure_reason;
    if (const std::optional<GapflytCrossing>& c = evaluation.crossing) {
      f["inside_opening"] = c->inside;
      f["clearance_m"] = c->clearance_m;
      f["centre_to_edge_m"] = c->centre_to_edge_m;
      f["crossing_offset_m"] = output::EigenToJson(c->offset_from_centroid_m);
      f["crossing_offset_norm_m"] = c->offset_from_centroid_m.norm();
      f["time_to_cross_s"] = c->t_s;
      if (!m.phase_changes().empty()) {
        for (const planning::GapflytPhaseChange& change : m.phase_changes()) {
          if (change.phase == planning::GapflytPhase::kServo) {
            f["servo_to_cross_s"] = c->t_s - change.t_s;
            break;
          }
        }
      }
      f["crossing_speed_mps"] = c->state.v_W.norm();
    }
    char line[240];
    if (evaluation.crossing) {
      std::snprintf(line, sizeof(line),
                    "gapflyt (%s): %s, clearance %.3f m, %.3f m from the centroid, crossed at "
                    "%.2f s",
                    servo::ToString(m.law()),
                    out.passed ? "passed the opening" : evaluation.failure_reason.c_str(),
                    evaluation.crossing->clearance_m,
                    evaluation.crossing->offset_from_centroid_m.norm(), evaluation.crossing->t_s);
    } else {
      std::snprintf(line, sizeof(line), "gapflyt (%s): %s (phase %s: %s)", servo::ToString(m.law()),
                    evaluation.failure_reason.c_str(), planning::ToString(m.phase()),
                    m.status().c_str());
    }
    out.outcome = line;
    return out;
  }

 private:
  const sim::Scenario& scenario_;
  control::VehicleParameters vehicle_;
  sim::CollisionParams collision_;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<planning::GapflytMission> mission_;
};

}  // namespace

std::unique_ptr<MissionFlight> MakeGapflytFlight(const MissionContext& context) {
  if (context.scenario.kind() != "gapflyt") {
    throw std::invalid_argument(
        "mission 'gapflyt' needs the gapflyt scenario (a wall with an "
        "opening), got '" +
        context.scenario.kind() + "': run `aperture sim gapflyt`");
  }
  return std::make_unique<GapflytFlight>(context);
}

}  // namespace aperture::experiments
