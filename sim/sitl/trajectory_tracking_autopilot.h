#pragma once
// SIMULATION ONLY: flies a control::ReferenceTrajectory on ground truth (Autopilot::
// OnGroundTruth), the motion-capture setting of the thesis experiments (F.7, G.6). Each Step(t)
// evaluates the reference at t (the simulator clock) and runs control::PositionController: flatness
// feed-forward (F.6-F.30) with or without rotor-drag compensation plus the position / attitude
// feedback of F.31-F.38 -> ThrustRatesCommand for the simulated flight controller (LQR or P body
// rates, mixer, saturation). It is GroundTruthAutopilot's controller with a moving reference
// instead of waypoints.
//
// Before the first ground-truth state it commands nothing (kNone). Once t exceeds the reference's
// EndTimeS() by settle_s the command reports done (the vehicle keeps holding the end point).
#include <memory>
#include <string>

#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/reference_trajectories.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"

namespace aperture::sim {

struct TrajectoryTrackingAutopilotParams {
  control::PositionControllerParams controller;  // Table A.2 gains, drag compensation on
  double settle_s = 1.0;  // hold at the end point this long after the reference stops [s]
  // Throws std::invalid_argument naming the field for a negative / non-finite settle_s or gain.
  void Validate() const;
};

class TrajectoryTrackingAutopilot : public perception::Autopilot {
 public:
  // `vehicle` is the controller's model (mass, and the drag D, k_h it compensates); `reference`
  // must not be null. Throws std::invalid_argument for invalid parameters.
  TrajectoryTrackingAutopilot(const control::VehicleParameters& vehicle,
                              std::shared_ptr<const control::ReferenceTrajectory> reference,
                              const TrajectoryTrackingAutopilotParams& params = {});
  std::string name() const override { return "ground_truth_tracking"; }
  bool UsesGroundTruth() const override { return true; }
  void OnGroundTruth(const control::QuadState& state) override;
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  const control::PositionController& controller() const { return controller_; }

 private:
  std::shared_ptr<const control::ReferenceTrajectory> reference_;
  TrajectoryTrackingAutopilotParams params_;
  control::PositionController controller_;
  control::QuadState state_;
  bool have_state_ = false;
  double last_t_s_ = 0.0;
};

}  // namespace aperture::sim
