#include "experiments/gap/ground_truth_gap_autopilot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "planning/primitive_feasibility.h"

namespace aperture::experiments {
namespace {

planning::TraverseTrajectory PlanTraverse(const planning::GapPose& gap,
                                          const planning::TraverseParameters& parameters) {
  const planning::TraverseOptimizationResult result =
      planning::OptimizeTraverseTrajectory(gap, parameters);
  if (result.status != planning::TraverseOptimizationResult::Status::kSuccess) {
    std::ostringstream message;
    message << "GroundTruthGapAutopilot: no traverse trajectory through the gap: " << result;
    throw std::runtime_error(message.str());
  }
  return *result.trajectory;
}

// The shortest approach on the duration grid that is input-feasible and stays above the floor;
// the longest one when none is (the feedback then does what it can).
planning::MotionPrimitive PlanApproach(const control::VehicleParameters& vehicle,
                                       const control::QuadState& start,
                                       const planning::TraverseTrajectory& traverse,
                                       const GroundTruthGapAutopilotParams& params) {
  planning::FeasibilityLimits limits =
      planning::FeasibilityLimits::FromVehicle(vehicle, params.max_body_rate_radps);
  limits.max_thrust_mps2 *= params.thrust_margin;
  limits.Validate();
  const control::TrajectoryPoint target = traverse.Sample(0.0);
  planning::MotionPrimitive approach;
  for (double T = params.min_approach_s; T <= params.max_approach_s + 1e-9;
       T += params.approach_step_s) {
    approach = planning::MotionPrimitive(start.p_WB, Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero(), target.p_W, target.v_W,
                                         target.a_W, T);
    if (planning::CheckInputFeasibility(approach, limits) == planning::Feasibility::kFeasible &&
        planning::MinimumProjection(approach, Eigen::Vector3d::UnitZ()) >= params.min_height_m) {
      break;
    }
  }
  return approach;
}

// From the traverse's end state to rest at the distance a constant deceleration would need.
planning::MotionPrimitive PlanBrake(const planning::TraverseTrajectory& traverse,
                                    const GroundTruthGapAutopilotParams& params) {
  const control::TrajectoryPoint end = traverse.Sample(traverse.duration_s());
  Eigen::Vector3d stop_W = end.p_W + 0.5 * params.brake_s * end.v_W;
  stop_W.z() = std::max(stop_W.z(), params.min_height_m + 0.5);
  return planning::MotionPrimitive(end.p_W, end.v_W, end.a_W, stop_W, Eigen::Vector3d::Zero(),
                                   Eigen::Vector3d::Zero(), params.brake_s);
}

}  // namespace

void GroundTruthGapAutopilotParams::Validate() const {
  const auto require = [](bool ok, const char* field) {
    if (!ok) {
      throw std::invalid_argument(std::string("GroundTruthGapAutopilotParams.") + field +
                                  " is out of range (see ground_truth_gap_autopilot.h)");
    }
  };
  require(std::isfinite(hover_s) && hover_s >= 0.0, "hover_s");
  require(std::isfinite(min_approach_s) && min_approach_s > 0.0, "min_approach_s");
  require(std::isfinite(max_approach_s) && max_approach_s >= min_approach_s, "max_approach_s");
  require(std::isfinite(approach_step_s) && approach_step_s > 0.0, "approach_step_s");
  require(std::isfinite(thrust_margin) && thrust_margin > 0.0 && thrust_margin <= 1.0,
          "thrust_margin");
  require(std::isfinite(max_body_rate_radps) && max_body_rate_radps > 0.0, "max_body_rate_radps");
  require(std::isfinite(min_height_m), "min_height_m");
  require(std::isfinite(brake_s) && brake_s > 0.0, "brake_s");
  traverse.Validate();
  controller.Validate();
}

GroundTruthGapAutopilot::GroundTruthGapAutopilot(const control::VehicleParameters& vehicle,
                                                 const planning::GapPose& gap,
                                                 const control::QuadState& start,
                                                 const GroundTruthGapAutopilotParams& params)
    : params_((params.Validate(), params)),
      controller_(vehicle, params.controller),
      start_(start),
      traverse_(PlanTraverse(gap, params.traverse)),
      approach_(PlanApproach(vehicle, start, traverse_, params)),
      brake_(PlanBrake(traverse_, params)) {
  traverse_start_s_ = params_.hover_s + approach_.duration_s();
  brake_start_s_ = traverse_start_s_ + traverse_.duration_s();
}

void GroundTruthGapAutopilot::OnGroundTruth(const control::QuadState& state) {
  state_ = state;
  have_state_ = true;
}

control::TrajectoryPoint GroundTruthGapAutopilot::Reference(double t_s) const {
  control::TrajectoryPoint reference;
  if (t_s < params_.hover_s) {
    reference.p_W = start_.p_WB;
  } else if (t_s < traverse_start_s_) {
    reference = approach_.Sample(t_s - params_.hover_s);
  } else if (t_s < brake_start_s_) {
    reference = traverse_.Sample(t_s - traverse_start_s_);
  } else {
    reference = brake_.Sample(std::min(t_s - brake_start_s_, brake_.duration_s()));
    if (t_s - brake_start_s_ >= brake_.duration_s()) {
      reference.v_W.setZero();
      reference.a_W.setZero();
      reference.j_W.setZero();
      reference.s_W.setZero();
    }
  }
  reference.t_s = t_s;
  reference.heading_rad = traverse_.heading_rad();
  reference.heading_rate_radps = 0.0;
  reference.heading_acc_radps2 = 0.0;
  return reference;
}

perception::AutopilotCommand GroundTruthGapAutopilot::Step(double t_s) {
  last_step_s_ = t_s;
  perception::AutopilotCommand command;
  if (!have_state_) return command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(state_, Reference(t_s)).command;
  return command;
}

std::string GroundTruthGapAutopilot::status() const {
  if (last_step_s_ < params_.hover_s) return "hover";
  if (last_step_s_ < traverse_start_s_) return "approach";
  if (last_step_s_ < brake_start_s_) return "traverse";
  if (last_step_s_ < brake_start_s_ + brake_.duration_s()) return "brake";
  return "hover after the gap";
}

double GroundTruthGapAutopilot::traverse_start_time_s() const {
  return last_step_s_ >= traverse_start_s_ ? traverse_start_s_
                                           : std::numeric_limits<double>::quiet_NaN();
}

std::optional<control::QuadState> GroundTruthGapAutopilot::estimate() const {
  if (!have_state_) return std::nullopt;
  return state_;
}

GapTrialAutopilotFactory MakeGroundTruthGapAutopilotFactory(
    const GroundTruthGapAutopilotParams& params) {
  return [params](const GapTrialSetup& setup) -> std::unique_ptr<GapTrialAutopilot> {
    const Eigen::Isometry3d& T_WG = setup.scenario->scene().object("gap").T_WO;
    planning::GapPose gap;
    gap.p_WG = T_WG.translation();
    gap.R_WG = T_WG.linear();
    return std::make_unique<GroundTruthGapAutopilot>(setup.vehicle, gap, setup.initial_state,
                                                     params);
  };
}

}  // namespace aperture::experiments
