#include "experiments/gap/gap_mission_trial.h"

#include "experiments/gap/gap_mission_factory.h"

namespace aperture::experiments {
namespace {

class GapMissionTrial : public GapTrialAutopilot {
 public:
  explicit GapMissionTrial(std::unique_ptr<planning::GapMission> mission)
      : mission_(std::move(mission)) {}
  perception::Autopilot& autopilot() override { return *mission_; }
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
};

}  // namespace

GapTrialAutopilotFactory MakeGapMissionTrialFactory() {
  return [](const GapTrialSetup& setup) -> std::unique_ptr<GapTrialAutopilot> {
    return std::make_unique<GapMissionTrial>(
        MakeGapMission(*setup.scenario, setup.vehicle, setup.mission));
  };
}

}  // namespace aperture::experiments
