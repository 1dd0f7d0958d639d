#include "experiments/missions/forest_flight.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/yaml_write_archive.h"
#include "experiments/missions/odometry_adapter.h"
#include "output/json_eigen.h"
#include "perception/mono_depth/mono_depth_estimator.h"
#include "planning/mono_nav/forest_mission_params_io.h"
#include "sim/sim_params_io.h"

namespace aperture::experiments {
namespace {

// What `aperture sim forest` flies without --duration: the start-to-goal distance at the slowest
// mean speed `bench mononav` measured (22 m in 55.6 s over 40 layouts: 0.40 m/s, less a margin
// for denser layouts), plus the take-off and the final approach.
constexpr double kSlowestMeanSpeedMps = 0.35;
constexpr double kTakeOffAndFinalApproachS = 5.0;

int FrontCameraIndex(const sim::Scenario& scenario) {
  const std::vector<sim::ScenarioCamera>& cameras = scenario.cameras();
  for (int i = 0; i < static_cast<int>(cameras.size()); ++i) {
    if (cameras[i].name == "front" && cameras[i].T_BC) {
      if (!cameras[i].render.color) {
        throw std::invalid_argument(
            "forest mission: camera 'front' renders gray; the depth model needs colour: set "
            "cameras.front.color=true");
      }
      return i;
    }
  }
  throw std::invalid_argument("scenario '" + scenario.kind() +
                              "' has no body-mounted camera 'front' for the forest mission: add "
                              "one (cameras.front)");
}

// Per-frame cost of a flown mission [ms of thread CPU]: {"frames", "mean", "median", "max"}.
nlohmann::json ForestFrameTiming(const planning::ForestMission& mission, bool planning) {
  std::vector<double> ms;
  for (const planning::ForestFrameRecord& r : mission.frames()) {
    ms.push_back(1e3 * (planning ? r.planning_s : r.perception_s));
  }
  if (ms.empty()) return {{"frames", 0}};
  double sum = 0.0;
  for (double v : ms) sum += v;
  std::vector<double> sorted = ms;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return {{"frames", ms.size()},
          {"mean", sum / ms.size()},
          {"median", sorted[sorted.size() / 2]},
          {"max", *std::max_element(ms.begin(), ms.end())}};
}

class ForestFlight final : public MissionFlight {
 public:
  explicit ForestFlight(const MissionContext& context)
      : scene_(context.scenario.scene()), p_WB_start_(context.sitl.initial_state.p_WB) {
    params_.goal_W = context.scenario.params().forest.goal_m;
    params_.camera_id = FrontCameraIndex(context.scenario);
    static_cast<perception::ImuNoiseParams&>(params_.fusion.filter) = context.sitl.imu;
    odometry_ = LoadOdometryParams(context, 17);
    LoadParams(context.params, &params_);  // config::LoadParams: reads, rejects, validates
    const sim::ScenarioCamera& camera = context.scenario.cameras()[params_.camera_id];
    mission_ = std::make_unique<planning::ForestMission>(params_, camera.model, *camera.T_BC,
                                                         context.sitl.dynamics.vehicle,
                                                         perception::DefaultMonoDepthModel());
    adapter_ = MakeOdometryAdapter(mission_.get(), odometry_);
  }

  YAML::Node EffectiveParams() const override {
    YAML::Node node = config::DumpParams(params_);
    node["odometry"] = config::DumpParams(odometry_);
    return node;
  }

  perception::Autopilot& autopilot() override { return *adapter_; }
  double MinimumDurationS() const override {
    return (params_.goal_W - p_WB_start_).norm() / kSlowestMeanSpeedMps + kTakeOffAndFinalApproachS;
  }
  void DrawOverlay(cv::Mat& onboard_bgr) const override { mission_->DrawOverlay(onboard_bgr); }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    std::optional<std::string> collision;
    if (result.collision) collision = result.reason;
    const ForestEvaluation e =
        EvaluateForestFlight(result.trajectory, collision, params_.goal_W, scene_);
    const planning::ForestMission& m = *mission_;
    MissionEvaluation out;
    out.passed = e.success;
    nlohmann::json& f = out.figures;
    f["success"] = e.success;
    f["reached_goal"] = e.reached_goal;
    f["collision"] = e.collision;
    if (!e.success) f["failure_reason"] = e.failure_reason;
    f["time_to_goal_s"] = e.reached_goal ? nlohmann::json(e.time_to_goal_s) : nlohmann::json();
    f["path_length_m"] = e.path_length_m;
    f["min_clearance_m"] = e.min_clearance_m;
    f["nearest_obstacle"] = e.nearest_obstacle;
    f["final_distance_m"] = e.final_distance_m;
    f["min_distance_to_goal_m"] = e.min_distance_m;
    f["goal_m"] = output::EigenToJson(params_.goal_W);
    f["ego_dynamic"] = params_.ego_dynamic;
    f["waypoint_order"] =
        params_.waypoint_order == planning::WaypointOrder::kOptimal ? "optimal" : "random";
    f["replans"] = m.replans();
    f["selections"] = m.selections();
    f["frames_replanned"] = m.frames_replanned();
    f["frames"] = static_cast<int>(m.frames().size());
    f["frames_without_path"] = m.frames_without_path();
    f["back_offs"] = m.back_offs();
    f["look_asides"] = m.look_asides();
    f["recoveries"] = m.back_offs() + m.look_asides();
    f["turns_to_goal"] = m.turns_to_goal();
    f["perception_ms"] = ForestFrameTiming(m, false);
    f["planning_ms"] = ForestFrameTiming(m, true);
    f["odometry_fused"] = m.fusion_counts().applied;
    f["odometry_rejected"] = m.fusion_counts().rejected_outlier;
    f["filter_restarts"] = m.fusion_counts().restarts;
    char line[220];
    if (e.success) {
      std::snprintf(line, sizeof(line),
                    "forest: reached the goal in %.1f s, path %.1f m, %d replans, min clearance "
                    "%.2f m",
                    e.time_to_goal_s, e.path_length_m, m.replans(), e.min_clearance_m);
    } else {
      std::snprintf(line, sizeof(line),
                    "forest: FAILED (%s), %.1f m from the goal, min clearance %.2f m",
                    e.failure_reason.c_str(), e.final_distance_m, e.min_clearance_m);
    }
    out.outcome = line;
    return out;
  }

 private:
  const sim::Scene& scene_;
  Eigen::Vector3d p_WB_start_;
  planning::ForestMissionParams params_;
  sim::OdometrySensorParams odometry_;
  std::unique_ptr<planning::ForestMission> mission_;
  std::unique_ptr<OdometryAdapter> adapter_;
};

}  // namespace

std::unique_ptr<MissionFlight> MakeForestFlight(const MissionContext& context) {
  return std::make_unique<ForestFlight>(context);
}

}  // namespace aperture::experiments
