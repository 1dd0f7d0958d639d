#include "experiments/gap/gap_mission_trial.h"

#include "experiments/gap/gap_mission_factory.h"
#include "experiments/missions/odometry_adapter.h"

namespace aperture::experiments {
namespace {

class GapMissionTrial : public GapTrialAutopilot {
 public:
  // The recovery's visual odometry is simulated with the sensor's default noise.
  GapMissionTrial(std::unique_ptr<planning::GapMission> mission, const sim::Scenario& scenario)
      : mission_(std::move(mission)),
        adapter_(MakeOdometryAdapter(mission_.get(),
                                     OdometryParamsFor(scenario, kGapOdometrySalt))) {}
  perception::Autopilot& autopilot() override { return *adapter_; }
  std::optional<planning::TraverseTrajectory> traverse_plan() const override {
    return mission_->traverse_plan();
  }
  double traverse_start_time_s() const override { return mission_->traverse_start_time_s(); }
  std::optional<control::QuadState> estimate() const override {
    if (!mission_->has_estimate()) return std::nullopt;
    return mission_->estimate();
  }
  // The mission frame is fixed at the gap when the filter starts (gap_mission.h).
  std::optional<planning::GapPose> gap_estimate() const override {
    if (!mission_->has_estimate()) return std::nullopt;
    return mission_->gap_W();
  }

 private:
  std::unique_ptr<planning::GapMission> mission_;
  std::unique_ptr<OdometryAdapter> adapter_;
};

}  // namespace

GapTrialAutopilotFactory MakeGapMissionTrialFactory() {
  return [](const GapTrialSetup& setup) -> std::unique_ptr<GapTrialAutopilot> {
    return std::make_unique<GapMissionTrial>(
        MakeGapMission(*setup.scenario, setup.vehicle, setup.mission), *setup.scenario);
  };
}

}  // namespace aperture::experiments
