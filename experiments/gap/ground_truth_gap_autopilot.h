#pragma once
// SIMULATION ONLY: the gap flight of seed 000 on ground truth, the bench's reference for what the
// control stack achieves with a perfect state and a perfect gap pose (no camera, no filter).
// Hover at the start for hover_s -> approach: minimum-jerk motion primitive (planning/
// motion_primitive.h) from rest to the traverse's start state (p_0, v_0, a_0 of (3), (5)), the
// shortest duration on the grid that the recursive feasibility test accepts and that stays above
// min_height_m -> traverse (1)-(5) optimised by (6) on the true gap pose -> braking primitive
// to rest -> hover there. Every phase is tracked by control::PositionController (F.31-F.38) on
// the ground-truth state, heading fixed at the traverse heading.
#include <optional>
#include <string>

#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "experiments/gap/gap_trial_autopilot.h"
#include "perception/autopilot.h"
#include "planning/motion_primitive.h"
#include "planning/traverse_trajectory.h"

namespace aperture::experiments {

struct GroundTruthGapAutopilotParams {
  double hover_s = 0.5;  // hover at the start before the approach [s]
  planning::TraverseParameters traverse;  // (6): v_0,max = 3 m/s, d_min = 0.25 m
  // Approach durations tried in order, from min to max in steps [s]; the first feasible wins.
  double min_approach_s = 1.5;
  double max_approach_s = 6.0;
  double approach_step_s = 0.25;
  // Feasibility limits of the approach: this fraction of the vehicle's thrust range (margin for
  // the feedback) and a body-rate bound [rad/s].
  double thrust_margin = 0.8;
  double max_body_rate_radps = 8.0;
  double min_height_m = 0.5;  // lowest point of the approach and of the braking stop [m]
  double brake_s = 1.5;       // braking primitive: from the traverse end to rest [s]
  control::PositionControllerParams controller;  // Table A.2 gains
  // Throws std::invalid_argument naming the field for non-positive or inconsistent values.
  void Validate() const;
};

class GroundTruthGapAutopilot : public perception::Autopilot, public GapTrialAutopilot {
 public:
  // Plans everything at construction from the start state and the true gap. Throws
  // std::invalid_argument for invalid params and std::runtime_error when (6) has no solution.
  GroundTruthGapAutopilot(const control::VehicleParameters& vehicle, const planning::GapPose& gap,
                          const control::QuadState& start,
                          const GroundTruthGapAutopilotParams& params = {});

  // perception::Autopilot
  std::string name() const override { return "ground_truth_gap"; }
  bool UsesGroundTruth() const override { return true; }
  void OnGroundTruth(const control::QuadState& state) override;
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;

  // GapTrialAutopilot
  perception::Autopilot& autopilot() override { return *this; }
  std::optional<planning::TraverseTrajectory> traverse_plan() const override { return traverse_; }
  double traverse_start_time_s() const override;
  std::optional<control::QuadState> estimate() const override;
  std::optional<planning::GapPose> gap_estimate() const override { return traverse_.gap(); }

  // The reference flown at t_s (simulator time).
  control::TrajectoryPoint Reference(double t_s) const;
  double approach_duration_s() const { return approach_.duration_s(); }

 private:
  GroundTruthGapAutopilotParams params_;
  control::PositionController controller_;
  control::QuadState start_;
  planning::TraverseTrajectory traverse_;
  planning::MotionPrimitive approach_;
  planning::MotionPrimitive brake_;
  double traverse_start_s_ = 0.0;
  double brake_start_s_ = 0.0;
  control::QuadState state_;
  bool have_state_ = false;
  double last_step_s_ = 0.0;
};

// Builds a GroundTruthGapAutopilot from the scenario's true "gap" object pose and the start state.
GapTrialAutopilotFactory MakeGroundTruthGapAutopilotFactory(
    const GroundTruthGapAutopilotParams& params = {});

}  // namespace aperture::experiments
