#pragma once
// Recovery after a hand throw (Faessler thesis paper B, B.3, B.4.2) as a perception::Autopilot:
// control::RecoveryPipeline fed by the delivered IMU samples (launch detection B.29, attitude
// estimator B.22-B.26, height prediction B.27) and downward range readings (B.28); its five-stage
// state machine (B.3.2) gives the ThrustRatesCommand for the flight controller. Before launch the
// motors idle (kNone).
//
// SIMULATION ONLY for one input: the vision pipeline (SVO in the thesis) is emulated by
// sim::VisualInitialization from ground truth. It tries to initialize from the height stage (3)
// on, as SVO does while the vehicle drifts, and fails while the vehicle is too close to the
// ground, too tilted or too fast for its downward camera; once initialized its estimate is
// delayed, noisy and off in scale by the height estimate's error. Like a visual-inertial estimate
// it is given in a gravity-aligned vision frame V whose heading matches the IMU attitude
// estimator's (whose yaw is otherwise arbitrary: unobservable from the accelerometer): at
// initialization R_VW = Rz(psi_estimator - psi_true). The command is done once the position
// stage (5) has held for hold_s.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "control/quad_state.h"
#include "control/recovery_pipeline.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "sim/sitl/visual_initialization.h"

namespace aperture::sim {

struct RecoveryAutopilotParams {
  control::RecoveryPipelineParams pipeline;
  VisualInitializationParams vision;
  std::uint64_t vision_seed = 1;  // the vision emulation's noise and scale error
  // Position hold before done [s]: the IMU-only attitude estimate, off by up to ~15 deg after the
  // braking stages (accelerometer = thrust + drag, B.2.5), re-converges within ~3 s of hover.
  double hold_s = 4.0;
  // Throws std::invalid_argument naming the field (negative / non-finite times, vision params).
  void Validate() const;
};

class RecoveryAutopilot : public perception::Autopilot {
 public:
  // `vehicle` is the controller's model. Throws std::invalid_argument for invalid parameters.
  RecoveryAutopilot(const control::VehicleParameters& vehicle,
                    const RecoveryAutopilotParams& params = {});
  std::string name() const override { return "recovery_hand_throw"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnRange(const perception::RangeReading& reading) override;
  bool UsesGroundTruth() const override { return true; }  // vision emulation only
  void OnGroundTruth(const control::QuadState& state) override { truth_ = state; }
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  const control::RecoveryPipeline& pipeline() const { return pipeline_; }
  // Time the vision pipeline initialized [s] (< 0: not yet).
  double vision_available_s() const { return vision_.initialized_at_s(); }
  const VisualInitialization& vision() const { return vision_; }

 private:
  RecoveryAutopilotParams params_;
  control::RecoveryPipeline pipeline_;
  control::QuadState truth_;
  VisualInitialization vision_;
};

}  // namespace aperture::sim
