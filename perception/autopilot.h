#pragma once
// The autonomy side of the sensor / vehicle boundary (DESIGN.md "Layout and layering"): sensor
// data in (perception/sensor_data.h), vehicle commands out (control/commands.h). The same
// Autopilot runs against the simulator (sim/sitl/sitl_runner.h), a recorded sequence or real
// hardware, so nothing here knows about sim/.
//
// Calling contract (the driver is the SITL runner or a hardware node; all times on the data
// source's clock, the simulator clock in SITL):
//   * OnImu / OnFrame / OnRange are called when a measurement is *delivered* (after its latency),
//     in delivery order (the SITL runner delivers per 1 ms step: IMU, then range, then frames),
//     each sample's own t_s being its measurement time.
//   * Step(t_s) is called at the high-level control rate (50-100 Hz typically) with the current
//     time, after every measurement delivered up to t_s; it returns the command to apply from now
//     on. The driver holds the last command until the next Step.
//   * OnGroundTruth is SIMULATION ONLY: a driver calls it (before each Step) only for autopilots
//     whose UsesGroundTruth() is true. Mission autopilots that must fly on hardware return false
//     and never see ground truth.
#include <string>

#include "control/commands.h"
#include "control/quad_state.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

struct AutopilotCommand {
  enum class Kind {
    kNone,          // no command (yet): the flight controller idles the motors
    kThrustRates,   // thrust_rates goes through the flight controller's body-rate loop + mixer
    kRotorThrusts,  // rotor_thrusts is passed straight to the motors
  };
  Kind kind = Kind::kNone;
  control::ThrustRatesCommand thrust_rates;
  control::RotorThrustCommand rotor_thrusts;
  // True once the autopilot has finished its mission; the driver may end the run.
  bool done = false;
};

class Autopilot {
 public:
  virtual ~Autopilot() = default;
  // Short identifier for logs and summaries, e.g. "ground_truth_hover".
  virtual std::string name() const = 0;
  virtual void OnImu(const ImuSample& /*sample*/) {}
  // frame.camera_id indexes the rig's cameras (the order the driver was configured with).
  virtual void OnFrame(const Frame& /*frame*/) {}
  // false promises that OnFrame ignores a frame of camera camera_id stamped t_s, whenever it is
  // delivered from now on; a simulator may then skip rendering it (sim/sitl/sitl_runner.h).
  virtual bool WantsFrame(int /*camera_id*/, double /*t_s*/) const { return true; }
  virtual void OnRange(const RangeReading& /*reading*/) {}
  // Simulation only (see above): true if the autopilot needs OnGroundTruth.
  virtual bool UsesGroundTruth() const { return false; }
  virtual void OnGroundTruth(const control::QuadState& /*state*/) {}
  // High-level control step at t_s [s]; see the calling contract above.
  virtual AutopilotCommand Step(double t_s) = 0;
  // One line describing the current mode/phase for logs ("hover", "waypoint 2/4", ...).
  virtual std::string status() const { return {}; }
};

}  // namespace aperture::perception
