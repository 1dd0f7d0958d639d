#pragma once
// SIMULATION ONLY: a hover / waypoint autopilot flying on ground truth (Autopilot::
// OnGroundTruth), so every scenario can be flown before mission behaviours exist. Cascade:
// position PD with gravity (and rotor-drag) compensation -> desired thrust direction and collective
// thrust -> attitude controller -> body rates, i.e. control::PositionController (Faessler thesis
// F.31-F.38 with the paper-B attitude controller) on a constant reference at the active waypoint.
// The output is a ThrustRatesCommand for the simulated flight controller.
//
// Waypoints are flown in order: the reference jumps to the next one after the vehicle has stayed
// within arrival_radius_m of the current one for its hold_s. The position error fed to the PD law
// is clamped to max_position_error_m, which bounds the commanded acceleration (and tilt) on long
// legs. After the last waypoint's hold, the command reports done (if finish_when_done) and the
// vehicle keeps hovering there. Before the first ground-truth state it commands nothing (kNone).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"

namespace aperture::sim {

struct Waypoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // [m]
  double heading_rad = 0.0;
  double hold_s = 0.0;  // time to stay within the arrival radius before moving on [s]
};

struct GroundTruthAutopilotParams {
  std::vector<Waypoint> waypoints;  // at least one; a single waypoint = hover
  double arrival_radius_m = 0.1;
  double max_position_error_m = 1.0;  // ~5 m/s^2 with the default p_xy = 5 (~27 deg tilt)
  bool finish_when_done = false;      // false: hover at the last waypoint until the run ends
  control::PositionControllerParams controller;  // Table A.2 gains
  // Throws std::invalid_argument naming the field (no waypoints, non-finite values, radii <= 0,
  // negative hold times).
  void Validate() const;
};

class GroundTruthAutopilot : public perception::Autopilot {
 public:
  // `vehicle`: the controller's vehicle model (mass, drag). Throws for invalid parameters.
  GroundTruthAutopilot(const control::VehicleParameters& vehicle,
                       const GroundTruthAutopilotParams& params);
  std::string name() const override { return "ground_truth_waypoints"; }
  bool UsesGroundTruth() const override { return true; }
  void OnGroundTruth(const control::QuadState& state) override;
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  int active_waypoint() const { return active_; }

 private:
  GroundTruthAutopilotParams params_;
  control::PositionController controller_;
  control::QuadState state_;
  bool have_state_ = false;
  int active_ = 0;
  double arrived_since_s_ = -1.0;  // < 0: not within the arrival radius
  bool done_ = false;
};

}  // namespace aperture::sim
