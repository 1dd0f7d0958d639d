#include "experiments/missions/builtin_missions.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "config/yaml_write_archive.h"
#include "experiments/led/led_hover_flight.h"
#include "experiments/led/led_hover_flight_params_io.h"
#include "experiments/missions/forest_flight.h"
#include "experiments/missions/gap_mission_flight.h"
#include "experiments/missions/gapflyt_flight.h"
#include "experiments/missions/tag_follow_flight.h"
#include "experiments/missions/tag_mapping_flight.h"
#include "sim/sitl/ground_truth_autopilot.h"

namespace aperture::experiments {
namespace {

// Largest distance from the start pose a ground-truth hover may reach and still pass [m]: the
// hover holds ~mm on ground truth (sitl tests), so 10 cm only fails a broken controller or a
// disturbance it could not reject.
constexpr double kHoverMaxErrorM = 0.1;

// Ground-truth hover at the start pose: the reference flight of scenarios without a mission.
class HoverFlight final : public MissionFlight {
 public:
  explicit HoverFlight(const MissionContext& context)
      : p_set_W_(context.sitl.initial_state.p_WB),
        autopilot_(context.sitl.dynamics.vehicle, Params(context)) {}

  perception::Autopilot& autopilot() override { return autopilot_; }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    MissionEvaluation out;
    const HoverMetrics hover = ComputeHoverMetrics(result.trajectory, p_set_W_, {}, kHoverMaxErrorM,
                                                   /*recovery_hold_s=*/1.0);
    out.figures["hover_error_m"] = {{"max", hover.max_error_m}, {"rms", hover.rms_error_m}};
    out.passed = !result.collision && hover.max_error_m <= kHoverMaxErrorM;
    char line[120];
    std::snprintf(line, sizeof(line), "hover (ground truth): %s, max error %.3f m",
                  out.passed ? "held" : "NOT held", hover.max_error_m);
    out.outcome = line;
    return out;
  }

 private:
  static sim::GroundTruthAutopilotParams Params(const MissionContext& context) {
    const Eigen::Matrix3d R_WB = context.scenario.T_WB_start().linear();
    sim::GroundTruthAutopilotParams params;
    params.waypoints.push_back(
        sim::Waypoint{context.sitl.initial_state.p_WB, std::atan2(R_WB(1, 0), R_WB(0, 0)), 0.0});
    return params;
  }

  Eigen::Vector3d p_set_W_;
  sim::GroundTruthAutopilot autopilot_;
};

// The LED-stabilized hover, passed when it held the set-point: no collision, every push
// recovered, and an RMS error outside the push recoveries within kLedHoverMaxRmsM.
class LedHoverMission final : public MissionFlight {
 public:
  // The LED issue's hover measured 1.8 cm RMS outside pushes in 1-2 m/s gusts; 5 cm fails a
  // hover that drifts or oscillates, not one that rides the gusts.
  static constexpr double kLedHoverMaxRmsM = 0.05;
  // The LED issue's 1 m/s push was back within 10 cm after 1.26 s and then has to stay there for
  // the recovery hold (1 s): 3 s leaves margin.
  static constexpr double kPushRecoveryBudgetS = 3.0;

  explicit LedHoverMission(const MissionContext& context)
      : pushes_(context.sitl.disturbances.pushes),
        params_(LoadedParams(context)),
        flight_(context.scenario, context.sitl, params_) {}

  perception::Autopilot& autopilot() override { return flight_.autopilot(); }
  YAML::Node EffectiveParams() const override { return config::DumpParams(params_); }
  void DrawOverlay(cv::Mat& onboard_bgr) const override { flight_.DrawOverlay(onboard_bgr); }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    result_ = flight_.Finish(result, pushes_);
    MissionEvaluation out;
    out.figures = LedHoverSummary(*result_);
    // A push must have been recovered unless the run ended within kPushRecoveryBudgetS of it.
    bool recovered = true;
    for (const PushRecovery& push : result_->hover.pushes) {
      recovered &= push.recovery_time_s.has_value() ||
                   result.sim_time_s - push.t_push_s < kPushRecoveryBudgetS;
    }
    out.passed = !result.collision && recovered &&
                 result_->hover.rms_error_outside_pushes_m <= kLedHoverMaxRmsM;
    char line[160];
    std::snprintf(line, sizeof(line),
                  "LED hover: %s, RMS error %.3f m (%.3f m outside pushes), %d/%d frames with a "
                  "pose",
                  out.passed ? "held" : "NOT held", result_->hover.rms_error_m,
                  result_->hover.rms_error_outside_pushes_m, result_->counts.frames_with_pose,
                  result_->counts.frames);
    out.outcome = line;
    return out;
  }

  void AddReportSections(const MissionEvaluation& /*evaluation*/, const sim::SitlResult& /*result*/,
                         output::HtmlReport* report) const override {
    if (result_) AddLedHoverReport(*result_, report);
  }

 private:
  static LedHoverFlightParams LoadedParams(const MissionContext& context) {
    LedHoverFlightParams params;
    LoadParams(context.params, &params);  // config::LoadParams: reads, rejects, validates
    return params;
  }

  std::vector<sim::Push> pushes_;
  LedHoverFlightParams params_;
  LedHoverFlight flight_;
  std::optional<LedHoverFlightResult> result_;  // of Evaluate
};

}  // namespace

void RegisterBuiltinMissions(MissionRegistry& registry) {
  registry.Register("gap",
                    "vision gap mission (seed 000): detect, plan, approach, traverse the "
                    "patterned gap, recover",
                    {"gap"}, MakeGapMissionFlight);
  registry.Register("gapflyt",
                    "GapFlyt (seed 002): active scan, TS2P detection, label tracking, servo "
                    "(servo.law moments | pid) through the unknown opening",
                    {"gapflyt"}, MakeGapflytFlight);
  registry.Register("led_hover",
                    "LED-stabilized hover (thesis C.4.3): LED pose from the ground camera + IMU",
                    {"led"}, [](const MissionContext& context) -> std::unique_ptr<MissionFlight> {
                      return std::make_unique<LedHoverMission>(context);
                    });
  registry.Register("forest",
                    "forest navigation (seed 003): monocular depth, ego-dynamic space, waypoint, "
                    "minimum-time B-spline, replanned every frame, to forest.goal_m",
                    {"forest"}, MakeForestFlight);
  registry.Register("map",
                    "tag mapping flight (seed 001, paper D): lawn-mower coverage of the tag field, "
                    "apriltag front end, incremental tag map, scored on the ground truth",
                    {}, MakeTagMappingFlight);
  registry.Register("follow",
                    "ground robot executing its planned mission (seed 001, paper D Alg. 2/3) "
                    "while the quadrotor follows it by visual servoing on its tag (ViSP points)",
                    {}, MakeTagFollowFlight);
  registry.Register("deliver",
                    "paper D's whole mission (seed 001): mapping flight, tag map, the ground "
                    "robot's mission planned on it and executed with relocalization while the "
                    "quadrotor follows; the first-aid kit onto the goal",
                    {"tags"}, MakeTagDeliveryFlight);
  registry.Register("hover", "hover at the start pose on ground truth (reference flight)", {},
                    [](const MissionContext& context) -> std::unique_ptr<MissionFlight> {
                      return std::make_unique<HoverFlight>(context);
                    });
}

}  // namespace aperture::experiments
