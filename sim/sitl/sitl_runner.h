#pragma once
// Lockstep software-in-the-loop runner: one simulator clock drives the vehicle, its sensors, the
// simulated flight controller and any perception::Autopilot (perception/autopilot.h), so a run is
// a deterministic function of its parameters and seeds, however slow the rendering.
//
// Per dynamics step k (t = k / dynamics_rate_hz), in this order:
//   1. sensors sample the state at t: IMU (sim/sensors/imu_sensor.h: its own rate, noise,
//      latency), range sensor, cameras due at their rate. A camera frame's exposure ends at t
//      (mid-exposure stamp t - exposure_s / 2, motion blur over the exposure from the recorded
//      pose history); it is dropped with probability drop_probability (seeded, not rendered) or
//      lost in one of the camera's outage windows, or rendered (sim/render: the camera's model at T_WB * T_BC, camera_effects noise) and
//      delivered at t + latency_s. Range readings are delivered latency_s after t.
//   2. everything delivered by t goes to the autopilot (IMU also to the flight controller's gyro);
//   3. at the control rate: ground truth (only if the autopilot UsesGroundTruth(); the state of
//      t - estimate_latency_s), then Autopilot::Step(t); the command reaches the flight
//      controller command_latency_s later;
//   4. at the flight-controller rate: SimulatedFlightController -> rotor thrust commands ->
//      motor commands through its model's inverse thrust map, which reach the motors
//      esc_delay_s later;
//   5. the vehicle advances by one step under the disturbances (sim/vehicle/disturbances.h);
//   6. collision check (sim/sitl/collision_checker.h), and with ground contact on
//      (dynamics.ground_contact_enabled) the touchdown check of a step that landed.
// The run ends at duration_s, when a command has done == true, on the first collision, or when
// SitlHooks::stop_requested says so (checked once per dynamics step, before step 1).
//
// Ground: the plane z_W = dynamics.ground_height_m, for the dynamics and the collision checker.
// By default it is a wall like any other (the run ends when the body sphere or a propeller
// reaches it). With dynamics.ground_contact_enabled the vehicle has landing gear
// (dynamics.landing_gear_height_m > collision.body_radius_m): it can start on the ground
// (initial p_z = ground + gear height, typically with start_hovering = false) and take off, and
// a touchdown within collision.max_touchdown_speed_mps / max_touchdown_tilt_rad leaves it resting
// on the gear and the run going (it lifts off again when the thrust exceeds its weight); a harder
// one ends the run as "collision: landing gear with 'ground'" at the point below B.
//
// Usage:
//   SitlRunnerParams params;              // 1 kHz dynamics + flight controller, 500 Hz IMU
//   params.initial_state.p_WB = {0, 0, 1.5};
//   params.cameras.push_back(camera);     // SitlCamera{name, model, T_BC, rate_hz, ...}
//   params.SetSeed(7);                    // every noise and drop stream from one seed
//   SitlRunner runner(params, &scene);
//   GroundTruthAutopilot autopilot(...);  // or any perception::Autopilot
//   SitlResult result = runner.Run(autopilot);
//   result.outcome, result.collision, result.trajectory, result.real_time_factor ...
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/sensor_data.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"
#include "sim/render/render_profile.h"
#include "sim/scene/scene.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/fixed_camera_renderer.h"
#include "sim/sitl/simulated_flight_controller.h"
#include "sim/vehicle/disturbances.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

// A span of simulator time [start_s, end_s) [s].
struct TimeWindow {
  double start_s = 0.0;
  double end_s = 0.0;
  bool Contains(double t_s) const { return t_s >= start_s && t_s < end_s; }
};

// One onboard camera. Its index in SitlRunnerParams::cameras is the Frame::camera_id.
struct SitlCamera {
  std::string name = "camera";
  std::shared_ptr<const perception::CameraModel> model;    // required
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();  // camera pose in B
  // Set for a camera fixed in the world (an external observer, e.g. of the LED target): its pose
  // T_WC; T_BC is then unused.
  std::optional<Eigen::Isometry3d> T_WC_fixed;
  double rate_hz = 30.0;
  double latency_s = 0.0;         // end of exposure -> delivery [s]
  double drop_probability = 0.0;  // in [0, 1): frames lost (driver / transport)
  // Outages (a blinded or disconnected camera): frames whose exposure ends inside one of these
  // windows are lost like drops (SitlCameraStats::frames_dropped), after the drop draw, so the
  // drop stream of the other frames is unchanged.
  std::vector<TimeWindow> outages;
  CameraEffectsParams effects;    // noise, gain, exposure + motion blur, infrared
  RenderOptions render;           // gray by default; ground_truth off saves time
};

struct SitlRunnerParams {
  double duration_s = 10.0;
  double dynamics_rate_hz = 1000.0;  // >= flight controller and IMU rates
  double control_rate_hz = 100.0;    // Autopilot::Step rate
  double command_latency_s = 0.0;    // autopilot -> flight controller [s]
  // Ground truth reaches an autopilot that uses it (UsesGroundTruth) this much later: it gets the
  // recorded state of t - estimate_latency_s (the state at t = 0 before that), stamped with its
  // own time [s]. The motion-capture estimate's age; resolution one dynamics step.
  double estimate_latency_s = 0.0;
  // Motor commands reach the motors this much after the flight controller issues them (ESC
  // delay) [s].
  double esc_delay_s = 0.0;
  QuadrotorDynamicsParams dynamics;  // the simulated vehicle
  // The flight controller's model of the vehicle (LQR torque estimate, mixer, and the inverse
  // thrust map (G.3) that turns its thrusts into motor commands); unset: dynamics.vehicle, a
  // perfectly identified vehicle. sim/sitl/vehicle_mismatch.h sets it to the nominal model.
  std::optional<control::VehicleParameters> flight_controller_model;
  // true: the run starts with every rotor settled at hover thrust (airborne start).
  bool start_hovering = true;
  control::QuadState initial_state;  // t_s is ignored: the clock starts at 0
  DisturbanceParams disturbances;
  SimulatedFlightControllerParams flight_controller;
  ImuSensorParams imu;
  bool range_enabled = true;
  // Measures to the ground (dynamics.ground_height_m) and the scene's objects except
  // collision.ignored_objects (the parts attached to the body).
  RangeSensorParams range;
  double range_latency_s = 0.0;
  std::vector<SitlCamera> cameras;
  CollisionParams collision;
  std::uint64_t drop_seed = 3;  // frame-drop stream
  // World-fixed cameras (SitlCamera::T_WC_fixed) re-render per frame only where objects that
  // moved can appear (sim/sitl/fixed_camera_renderer.h: same images; valid while the hooks change
  // only object poses between frames, not materials, lighting or sky).
  bool reuse_fixed_camera_background = true;
  // false: a due frame that the autopilot says it would ignore (Autopilot::WantsFrame) is not
  // rendered nor delivered (SitlCameraStats::frames_skipped); the drop draw happens first, so
  // the other frames and the flight are the same. true: every frame (e.g. for a video).
  bool render_ignored_frames = true;
  // Records every n-th dynamics step in SitlResult::trajectory (1 = all).
  int trajectory_decimation = 1;
  // > 0: SitlResult keeps only about the last record_window_s of its trajectory, commands, IMU
  // samples and range readings (between one and two windows, sim/sitl/record_window.h), so a long
  // flight's memory stays flat (aperture bench soak); 0 keeps the whole flight [s].
  double record_window_s = 0.0;
  // Sets every random stream from one seed: IMU, range, camera noise (per camera) and drops.
  void SetSeed(std::uint64_t seed);
  // Throws std::invalid_argument naming the field for non-positive rates or durations, a
  // dynamics rate below the flight controller / IMU rate, negative latencies, a drop probability
  // outside [0, 1), a camera without model, and (via the components) invalid sub-parameters.
  void Validate() const;
};

struct SitlCommandRecord {
  double t_s = 0.0;
  perception::AutopilotCommand command;                       // as returned by Autopilot::Step
  Eigen::Vector4d rotor_thrusts_N = Eigen::Vector4d::Zero();  // flight-controller output at t_s
};

struct SitlCameraStats {
  std::string name;
  int frames_due = 0;
  int frames_dropped = 0;
  int frames_delivered = 0;
  int frames_skipped = 0;  // not rendered (render_ignored_frames = false)
};

// The same stages in process CPU seconds (perception/cpu_time.h: every thread, so the renderer's
// oneTBB workers count; exact while this flight is alone in the process, e.g. `aperture sim` or
// a bench on one thread). The autopilot's time is split into perception (Autopilot::OnFrame) and
// control (every other Autopilot call: IMU, range, ground truth, Step); total_s is the whole Run,
// so total_s - the stages is what ran beside them (e.g. a background video encoder).
struct SitlCpuProfile {
  double total_s = 0.0;
  double dynamics_s = 0.0;
  double render_s = 0.0;  // = render.total_s() + the time between the renderer's stages
  double perception_s = 0.0;
  double control_s = 0.0;
  double collision_s = 0.0;
  double hooks_s = 0.0;
  RenderProfile render;  // the render stages (render_profile.h)

  double stages_s() const {
    return dynamics_s + render_s + perception_s + control_s + collision_s + hooks_s;
  }
};

struct SitlTiming {  // wall time [s] per stage
  double wall_time_s = 0.0;
  double dynamics_s = 0.0;   // vehicle, disturbances, sensors, flight controller
  double render_s = 0.0;     // ray casting + camera effects of the onboard cameras
  double autopilot_s = 0.0;  // every Autopilot call
  double collision_s = 0.0;
  double hooks_s = 0.0;  // SitlHooks callbacks (the caller's scene updates, videos, views)
  SitlCpuProfile cpu;
};

struct SitlResult {
  enum class Outcome { kDurationReached, kAutopilotDone, kCollision, kStopped };
  Outcome outcome = Outcome::kDurationReached;
  std::string reason;  // human-readable, e.g. "collision: body with 'wall'"
  std::optional<Collision> collision;
  double sim_time_s = 0.0;        // simulated time at the end of the run
  double real_time_factor = 0.0;  // sim_time_s / timing.wall_time_s
  SitlTiming timing;
  std::string autopilot_name;
  std::string autopilot_status;  // Autopilot::status() at the end
  // The whole flight, or its last SitlRunnerParams::record_window_s when that is set.
  std::vector<control::QuadState> trajectory;   // ground truth, t = 0 first
  std::vector<SitlCommandRecord> commands;      // one per control step
  std::vector<perception::ImuSample> imu;       // as delivered
  std::vector<perception::RangeReading> range;  // as delivered
  std::vector<SitlCameraStats> cameras;
};
// "duration_reached", "autopilot_done", "collision", "stopped"
const char* ToString(SitlResult::Outcome outcome);

// Optional callbacks into a run.
struct SitlHooks {
  // Called before every camera frame is rendered, with the time at the end of exposure and the
  // vehicle state then: the owner of the (mutable) scene moves objects here (scripted targets,
  // objects attached to the body). Called once per frame, so motion blur sees them static.
  std::function<void(double t_s, const control::QuadState& state)> before_render;
  // Every rendered frame (before its delivery latency): camera index, the capture with its
  // ground truth, the vehicle state at the end of exposure. For videos and reports.
  std::function<void(int camera_index, const CapturedFrame& frame, const control::QuadState&)>
      on_frame;
  // Asked before every dynamics step: true ends the run there (outcome kStopped), with the
  // result of the steps so far (e.g. Ctrl-C, output/interruption.h).
  std::function<bool()> stop_requested;
};

class SitlRunner {
 public:
  // `scene` (may be null: no cameras allowed then, ground-only collisions) must outlive the
  // runner. Throws std::invalid_argument for invalid params.
  SitlRunner(const SitlRunnerParams& params, const Scene* scene);
  ~SitlRunner();
  // Runs one flight from params.initial_state; each call starts afresh (same seeds -> same run).
  SitlResult Run(perception::Autopilot& autopilot, const SitlHooks& hooks = {});
  const SitlRunnerParams& params() const { return params_; }

 private:
  SitlRunnerParams params_;
  const Scene* scene_;
  RayCaster ray_caster_;
};

}  // namespace aperture::sim
