#pragma once
// What `aperture bench gap` needs from the autopilot it flies through the gap: the autopilot
// itself plus read access to its traverse plan (for the Table I errors) and its state estimate
// (for the Fig. 6 plots). The bench builds one per trial through a GapTrialAutopilotFactory, so
// the same harness flies the vision mission and a ground-truth reference.
#include <functional>
#include <memory>
#include <optional>

#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "planning/gap_mission/gap_mission.h"
#include "planning/traverse_trajectory.h"
#include "sim/scenario/scenario.h"
#include "sim/sensors/imu_sensor.h"

namespace aperture::experiments {

class GapTrialAutopilot {
 public:
  virtual ~GapTrialAutopilot() = default;
  // The autopilot the SITL flies; lives as long as this object.
  virtual perception::Autopilot& autopilot() = 0;
  // The traverse plan in the autopilot's world frame (with its gap estimate), nullopt before it
  // has one; the last plan once the traverse has started.
  virtual std::optional<planning::TraverseTrajectory> traverse_plan() const = 0;
  // Simulator time the plan's t = 0 was flown from; NaN before the traverse.
  virtual double traverse_start_time_s() const = 0;
  // The autopilot's current state estimate in its world frame; nullopt when it has none.
  virtual std::optional<control::QuadState> estimate() const = 0;
  // The gap pose it flies through, in its world frame; nullopt when it has none. A mission may
  // fix its own world frame (e.g. at the gap); the bench compares its estimate with the ground
  // truth through this pose (estimate relative to the estimated gap, mapped onto the true gap).
  virtual std::optional<planning::GapPose> gap_estimate() const = 0;
};

// Everything a trial's autopilot may be built from. Mission autopilots use only what a real
// vehicle knows (cameras and their mounts from scenario->cameras(), the gap's size from
// scenario->params().gap, the vehicle model, the start state); simulation-only references may
// also read the true gap pose from scenario->scene().
struct GapTrialSetup {
  const sim::Scenario* scenario = nullptr;
  control::VehicleParameters vehicle;
  control::QuadState initial_state;
  double control_rate_hz = 100.0;
  // The IMU's specification (noise densities, random walks) as a datasheet gives it: the
  // nominal sim::ImuSensorParams, not the trial's randomized noise and biases.
  sim::ImuSensorParams imu;
  // The vision mission's effective parameters (the same for every trial of a bench): what the base
  // scenario defines (GapMissionParamsFor) with the `mission` configuration section applied.
  planning::GapMissionParams mission;
};

using GapTrialAutopilotFactory =
    std::function<std::unique_ptr<GapTrialAutopilot>(const GapTrialSetup& setup)>;

}  // namespace aperture::experiments
