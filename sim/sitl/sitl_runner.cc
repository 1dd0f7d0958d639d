#include "sim/sitl/sitl_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "control/require.h"
#include "perception/cpu_time.h"
#include "perception/elapsed_time.h"
#include "sim/sensors/sample_schedule.h"
#include "sim/sitl/record_window.h"

namespace aperture::sim {
namespace {

using Clock = std::chrono::steady_clock;

using perception::ProcessCpuSeconds;
using perception::ScopedCpuTimer;
using perception::SecondsSince;

// Adds the wall time of its lifetime to *wall_s and the process CPU time to *cpu_s.
class SectionTimer {
 public:
  SectionTimer(double* wall_s, double* cpu_s) : wall_s_(wall_s), cpu_(cpu_s) {}
  ~SectionTimer() { *wall_s_ += SecondsSince(start_); }
  SectionTimer(const SectionTimer&) = delete;
  SectionTimer& operator=(const SectionTimer&) = delete;

 private:
  double* wall_s_;
  Clock::time_point start_ = Clock::now();
  ScopedCpuTimer cpu_;
};

// Ground-truth poses of the last few steps, for motion blur over an exposure that ends now.
class PoseHistory {
 public:
  explicit PoseHistory(double span_s) : span_s_(span_s) {}
  void Add(const control::QuadState& state) {
    states_.push_back(state);
    while (states_.size() > 2 && states_.back().t_s - states_[1].t_s >= span_s_) {
      states_.pop_front();
    }
  }
  // T_WB at t_s: linear in position, slerp in attitude; clamped to the recorded span.
  // With a single recorded state (the first frame of a run) that state's pose.
  Eigen::Isometry3d T_WB(double t_s) const {
    size_t i = std::min<size_t>(1, states_.size() - 1);
    while (i + 1 < states_.size() && states_[i].t_s < t_s) ++i;
    const control::QuadState& a = states_[i > 0 ? i - 1 : 0];
    const control::QuadState& b = states_[i];
    double s = (b.t_s > a.t_s) ? (t_s - a.t_s) / (b.t_s - a.t_s) : 1.0;
    s = std::min(1.0, std::max(0.0, s));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = a.q_WB.slerp(s, b.q_WB).toRotationMatrix();
    T.translation() = a.p_WB + s * (b.p_WB - a.p_WB);
    return T;
  }

 private:
  double span_s_;
  std::deque<control::QuadState> states_;
};

struct CameraRuntime {
  const SitlCamera* camera;
  CameraEffects effects;
  std::unique_ptr<FixedCameraRenderer> fixed;  // world-fixed cameras with reuse_background
  SampleSchedule schedule;
  std::deque<std::pair<double, perception::Frame>> in_flight;  // (delivery time, frame)
  int slot = 0;
  SitlCameraStats stats;
};

}  // namespace

const char* ToString(SitlResult::Outcome outcome) {
  switch (outcome) {
    case SitlResult::Outcome::kDurationReached:
      return "duration_reached";
    case SitlResult::Outcome::kAutopilotDone:
      return "autopilot_done";
    case SitlResult::Outcome::kCollision:
      return "collision";
    case SitlResult::Outcome::kStopped:
      return "stopped";
  }
  return "unknown";
}

void SitlRunnerParams::SetSeed(std::uint64_t seed) {
  // Distinct streams per consumer: splitmix-style odd multipliers keep them uncorrelated.
  const auto derive = [seed](std::uint64_t stream) {
    return seed * 0x9E3779B97F4A7C15ull + stream * 0xBF58476D1CE4E5B9ull;
  };
  imu.seed = derive(1);
  range.seed = derive(2);
  drop_seed = derive(3);
  for (size_t i = 0; i < cameras.size(); ++i) cameras[i].effects.seed = derive(10 + i);
}

void SitlRunnerParams::Validate() const {
  // Names as the user writes them: the `sitl` block of a scenario, cameras.<name>.<key>,
  // --duration.
  control::RequirePositive(duration_s, "the simulated duration (--duration) [s]");
  control::RequirePositive(dynamics_rate_hz, "sitl.dynamics_rate_hz");
  control::RequirePositive(control_rate_hz, "sitl.control_rate_hz");
  control::RequireNonNegative(command_latency_s, "sitl.command_latency_s");
  control::RequireNonNegative(range_latency_s, "sitl.range_latency_s");
  control::RequireNonNegative(estimate_latency_s, "sitl.estimate_latency_s");
  control::RequireNonNegative(esc_delay_s, "sitl.esc_delay_s");
  dynamics.Validate();
  if (flight_controller_model) flight_controller_model->Validate();
  disturbances.Validate();
  flight_controller.Validate();
  imu.Validate();
  range.Validate();
  CollisionChecker::Validate(dynamics, collision);  // both, and the landing gear against the body
  // Sensors and controllers sample once per dynamics step at most (sample_schedule.h).
  const double fastest =
      std::max({flight_controller.rate_hz, imu.rate_hz, control_rate_hz, range.rate_hz});
  control::Require(dynamics_rate_hz >= fastest * (1.0 - 1e-9), "sitl.dynamics_rate_hz",
                   dynamics_rate_hz,
                   "is below the fastest flight-controller / IMU / control / range rate; raise it");
  if (trajectory_decimation < 1) {
    throw std::invalid_argument("SitlRunnerParams.trajectory_decimation must be >= 1");
  }
  control::RequireNonNegative(record_window_s, "the record window (record_window_s) [s]");
  for (size_t i = 0; i < cameras.size(); ++i) {
    const SitlCamera& c = cameras[i];
    const std::string field = "cameras." + c.name + ".";
    if (!c.model) throw std::invalid_argument(field + "model is missing");
    control::RequirePositive(c.rate_hz, field + "rate_hz");
    control::RequireNonNegative(c.latency_s, field + "latency_s");
    control::Require(c.drop_probability >= 0.0 && c.drop_probability < 1.0,
                     field + "drop_probability", c.drop_probability, "must be in [0, 1)");
    control::Require(c.rate_hz <= dynamics_rate_hz, field + "rate_hz", c.rate_hz,
                     "exceeds sitl.dynamics_rate_hz");
    for (size_t w = 0; w < c.outages.size(); ++w) {
      const TimeWindow& window = c.outages[w];
      control::Require(std::isfinite(window.start_s) && std::isfinite(window.end_s) &&
                           window.end_s >= window.start_s,
                       field + "outages[" + std::to_string(w) + "].end_s", window.end_s,
                       "must be finite and not before its start");
    }
    if (!c.T_BC.matrix().allFinite() || (c.T_WC_fixed && !c.T_WC_fixed->matrix().allFinite())) {
      throw std::invalid_argument(field + "pose (T_BC / T_WC_fixed) is not finite");
    }
  }
}

SitlRunner::SitlRunner(const SitlRunnerParams& params, const Scene* scene)
    : params_(params), scene_(scene) {
  params_.Validate();
  if (scene_ == nullptr && !params_.cameras.empty()) {
    throw std::invalid_argument("SitlRunner: cameras need a scene to render (scene is null)");
  }
}

SitlRunner::~SitlRunner() = default;

namespace {

bool InOutage(const SitlCamera& camera, double t_s) {
  return std::any_of(camera.outages.begin(), camera.outages.end(),
                     [t_s](const TimeWindow& window) { return window.Contains(t_s); });
}

// One flight of SitlRunner::Run: the simulated parts, what is in flight between them, and one
// method per step of the lockstep loop (sitl_runner.h, "Per dynamics step k").
class SitlFlight {
 public:
  SitlFlight(const SitlRunnerParams& p, const Scene* scene, RayCaster* ray_caster,
             perception::Autopilot* autopilot, const SitlHooks& hooks, SitlResult* result)
      : p_(p),
        scene_(scene),
        ray_caster_(ray_caster),
        autopilot_(autopilot),
        hooks_(hooks),
        result_(result),
        dt_s_(1.0 / p.dynamics_rate_hz),
        steps_(std::lround(p.duration_s * p.dynamics_rate_hz)),
        vehicle_(p.dynamics, InitialState(p)),
        controller_rotor_(p.flight_controller_model.value_or(p.dynamics.vehicle).rotor),
        flight_controller_(p.flight_controller_model.value_or(p.dynamics.vehicle),
                           p.flight_controller),
        disturbances_(p.disturbances),
        imu_(p.imu),
        range_(p.range, MakeRangeWorld(p, scene)),
        collision_checker_(p.dynamics, p.collision),
        control_schedule_(p.control_rate_hz),
        flight_controller_schedule_(p.flight_controller.rate_hz),
        drop_rng_(p.drop_seed),
        history_(MaxExposure(p) + 2.0 * (1.0 / p.dynamics_rate_hz)),
        wants_ground_truth_(autopilot->UsesGroundTruth()) {
    StartRotors();
    for (const SitlCamera& camera : p.cameras) {
      cameras_.push_back(CameraRuntime{&camera,
                                       CameraEffects(camera.effects),
                                       nullptr,
                                       SampleSchedule(camera.rate_hz),
                                       {},
                                       0,
                                       {}});
      if (camera.T_WC_fixed && p.reuse_fixed_camera_background) {
        cameras_.back().fixed =
            std::make_unique<FixedCameraRenderer>(*camera.model, *camera.T_WC_fixed);
      }
      cameras_.back().stats.name = camera.name;
    }
    rotor_thrusts_.thrust_N = vehicle_.RotorThrusts_N();
  }

  // Steps until the autopilot is done, the duration is reached or the vehicle collides.
  void Fly() {
    result_->trajectory.push_back(vehicle_.state());
    history_.Add(vehicle_.state());
    if (p_.estimate_latency_s > 0.0) estimate_history_.push_back(vehicle_.state());
    for (long k = 0;; ++k) {
      const double t_s = k * dt_s_;
      if (hooks_.stop_requested && hooks_.stop_requested()) {
        result_->outcome = SitlResult::Outcome::kStopped;
        result_->reason = "stopped at t = " + std::to_string(t_s) + " s";
        break;
      }
      SampleSensors(t_s);
      CaptureFrames(t_s);
      const Clock::time_point section = Clock::now();
      const double section_cpu_s = ProcessCpuSeconds();
      const double perception_before_s = cpu().perception_s;
      Deliver(t_s);
      const bool done = StepAutopilot(t_s);
      result_->timing.autopilot_s += SecondsSince(section);
      cpu().control_s +=
          ProcessCpuSeconds() - section_cpu_s - (cpu().perception_s - perception_before_s);
      if (done) {
        result_->outcome = SitlResult::Outcome::kAutopilotDone;
        result_->reason = "autopilot done: " + autopilot_->status();
        break;
      }
      if (k >= steps_) {
        result_->outcome = SitlResult::Outcome::kDurationReached;
        result_->reason = "duration reached";
        break;
      }
      StepVehicle(k, t_s);
      if (CheckCollision()) break;
    }
    result_->sim_time_s = vehicle_.state().t_s;
    result_->autopilot_status = autopilot_->status();
    for (const CameraRuntime& runtime : cameras_) result_->cameras.push_back(runtime.stats);
  }

 private:
  static control::QuadState InitialState(const SitlRunnerParams& p) {
    control::QuadState initial = p.initial_state;
    initial.t_s = 0.0;
    return initial;
  }

  // The range ray sees what the vehicle can collide with: the ground and the scene's objects
  // except the collision checker's ignored ones (the parts attached to the body).
  static RangeWorld MakeRangeWorld(const SitlRunnerParams& p, const Scene* scene) {
    RangeWorld range_world{p.dynamics.ground_height_m, scene, {}};
    for (const std::string& name : p.collision.ignored_objects) {
      const int id = scene != nullptr ? scene->FindId(name) : -1;
      if (id >= 0) range_world.see_through_object_ids.push_back(id);
    }
    return range_world;
  }

  static double MaxExposure(const SitlRunnerParams& p) {
    double max_exposure_s = 0.0;
    for (const SitlCamera& camera : p.cameras) {
      max_exposure_s = std::max(max_exposure_s, camera.effects.exposure_s);
    }
    return max_exposure_s;
  }

  void StartRotors() {
    if (p_.start_hovering) {
      const control::VehicleParameters& vehicle_params = p_.dynamics.vehicle;
      control::RotorThrustCommand hover;
      hover.thrust_N.setConstant(vehicle_params.mass_kg * vehicle_params.gravity_mps2 / 4.0);
      vehicle_.SetRotorThrustCommand(hover);
      vehicle_.SettleRotors();
    }
    flight_controller_.ResetThrustEstimate(vehicle_.RotorThrusts_N());
  }

  SitlCpuProfile& cpu() { return result_->timing.cpu; }

  // Runs a SitlHooks callback outside the render profile (a chase view renders too), adding its
  // wall and CPU time to *wall_s and the profile's hooks_s.
  template <typename Callback>
  void RunHook(double* wall_s, const Callback& callback) {
    const RenderProfileScope not_rendering(nullptr);
    const SectionTimer timer(wall_s, &cpu().hooks_s);
    callback();
  }

  // Step 1a: IMU and range sensor sample the state at t_s.
  void SampleSensors(double t_s) {
    const SectionTimer timer(&result_->timing.dynamics_s, &cpu().dynamics_s);
    const control::QuadState& state = vehicle_.state();
    imu_samples_ = imu_.Update(t_s, vehicle_.SpecificForce_B(), state.omega_B);
    if (p_.range_enabled) {
      if (const std::optional<perception::RangeReading> reading = range_.Update(state)) {
        range_in_flight_.emplace_back(t_s + p_.range_latency_s, *reading);
      }
    }
  }

  // Step 1b: every camera due at t_s drops its frame or renders it (exposure ending at t_s) and
  // sends it on its way (delivery at t_s + latency_s).
  void CaptureFrames(double t_s) {
    const Clock::time_point section = Clock::now();
    const double section_cpu_s = ProcessCpuSeconds();
    double hooks_s = 0.0;  // inside this section, booked apart from rendering
    const double hooks_cpu_before_s = cpu().hooks_s;
    const control::QuadState& state = vehicle_.state();
    for (size_t c = 0; c < cameras_.size(); ++c) {
      CameraRuntime& runtime = cameras_[c];
      if (!runtime.schedule.Due(t_s)) continue;
      const int slot = runtime.slot++;
      ++runtime.stats.frames_due;
      const SitlCamera& camera = *runtime.camera;
      const bool drawn_drop =
          camera.drop_probability > 0.0 && uniform_(drop_rng_) < camera.drop_probability;
      if (drawn_drop || InOutage(camera, t_s)) {
        ++runtime.stats.frames_dropped;
        continue;
      }
      if (hooks_.before_render) RunHook(&hooks_s, [&] { hooks_.before_render(t_s, state); });
      const double t_mid_s = t_s - 0.5 * camera.effects.exposure_s;
      if (!p_.render_ignored_frames && !autopilot_->WantsFrame(static_cast<int>(c), t_mid_s)) {
        ++runtime.stats.frames_skipped;
        continue;
      }
      const Eigen::Isometry3d T_BC = camera.T_BC;
      const std::optional<Eigen::Isometry3d>& T_WC_fixed = camera.T_WC_fixed;
      const PoseHistory& history = history_;
      const auto T_WC_at = [&history, &T_BC, &T_WC_fixed](double t) {
        return T_WC_fixed ? *T_WC_fixed : Eigen::Isometry3d(history.T_WB(t) * T_BC);
      };
      CapturedFrame captured =
          runtime.fixed
              ? runtime.effects.Capture(
                    [&](const Eigen::Isometry3d&, const RenderOptions& options, RenderOutput* out) {
                      runtime.fixed->Render(*scene_, options, out);
                    },
                    T_WC_at, t_mid_s, slot, camera.render)
              : runtime.effects.Capture(*ray_caster_, *scene_, *camera.model, T_WC_at, t_mid_s,
                                        slot, camera.render);
      captured.frame.camera_id = static_cast<int>(c);
      if (hooks_.on_frame) {
        RunHook(&hooks_s, [&] { hooks_.on_frame(static_cast<int>(c), captured, state); });
      }
      runtime.in_flight.emplace_back(t_s + camera.latency_s, captured.frame);
    }
    result_->timing.render_s += SecondsSince(section) - hooks_s;
    result_->timing.hooks_s += hooks_s;
    cpu().render_s += ProcessCpuSeconds() - section_cpu_s - (cpu().hooks_s - hooks_cpu_before_s);
  }

  // Step 2: everything delivered by t_s goes to the autopilot (IMU also to the flight
  // controller's gyro).
  void Deliver(double t_s) {
    for (const perception::ImuSample& sample : imu_samples_) {
      flight_controller_.SetGyro(sample.omega_B);
      autopilot_->OnImu(sample);
      result_->imu.push_back(sample);
    }
    KeepLastWindow(&result_->imu, t_s, p_.record_window_s);
    const double due_s = DueTime(t_s);
    while (!range_in_flight_.empty() && range_in_flight_.front().first <= due_s) {
      autopilot_->OnRange(range_in_flight_.front().second);
      result_->range.push_back(range_in_flight_.front().second);
      range_in_flight_.pop_front();
    }
    KeepLastWindow(&result_->range, t_s, p_.record_window_s);
    for (CameraRuntime& runtime : cameras_) {
      while (!runtime.in_flight.empty() && runtime.in_flight.front().first <= due_s) {
        const ScopedCpuTimer timer(&cpu().perception_s);
        autopilot_->OnFrame(runtime.in_flight.front().second);
        ++runtime.stats.frames_delivered;
        runtime.in_flight.pop_front();
      }
    }
  }

  // Step 3, at the control rate: ground truth (if wanted), then Autopilot::Step; the command
  // leaves for the flight controller. Returns the command's `done`.
  bool StepAutopilot(double t_s) {
    if (!control_schedule_.Due(t_s)) return false;
    if (wants_ground_truth_) autopilot_->OnGroundTruth(EstimatedState(t_s));
    const perception::AutopilotCommand command = autopilot_->Step(t_s);
    commands_in_flight_.emplace_back(t_s + p_.command_latency_s, command);
    result_->commands.push_back(SitlCommandRecord{t_s, command, rotor_thrusts_.thrust_N});
    KeepLastWindow(&result_->commands, t_s, p_.record_window_s);
    return command.done;
  }

  // Steps 4-5: commands due reach the flight controller, which runs at its rate; the vehicle
  // advances one step under the disturbances.
  void StepVehicle(long k, double t_s) {
    const SectionTimer timer(&result_->timing.dynamics_s, &cpu().dynamics_s);
    const double due_s = DueTime(t_s);
    while (!commands_in_flight_.empty() && commands_in_flight_.front().first <= due_s) {
      flight_controller_.SetCommand(commands_in_flight_.front().second);
      commands_in_flight_.pop_front();
    }
    if (flight_controller_schedule_.Due(t_s)) {
      rotor_thrusts_ = flight_controller_.Step();
      // The inverse of (G.3) as the flight controller knows it (it does not know gamma_i).
      Eigen::Vector4d u;
      for (int i = 0; i < 4; ++i)
        u[i] = controller_rotor_.CommandFromThrust(rotor_thrusts_.thrust_N[i]);
      motor_commands_in_flight_.emplace_back(t_s + p_.esc_delay_s, u);
    }
    while (!motor_commands_in_flight_.empty() && motor_commands_in_flight_.front().first <= due_s) {
      vehicle_.SetMotorCommands(motor_commands_in_flight_.front().second);
      motor_commands_in_flight_.pop_front();
    }
    previous_p_WB_ = vehicle_.state().p_WB;
    was_on_ground_ = vehicle_.on_ground();
    disturbances_.StepVehicle(dt_s_, &vehicle_);
    if (!vehicle_.state().IsValid()) {
      throw std::runtime_error("SitlRunner: the vehicle state became invalid at t = " +
                               std::to_string(t_s) + " s (check the autopilot's commands)");
    }
    history_.Add(vehicle_.state());
    if (p_.estimate_latency_s > 0.0) estimate_history_.push_back(vehicle_.state());
    if ((k + 1) % p_.trajectory_decimation == 0) {
      result_->trajectory.push_back(vehicle_.state());
      KeepLastWindow(&result_->trajectory, vehicle_.state().t_s, p_.record_window_s);
    }
  }

  // Step 6: collision along the step, or a touchdown too hard for the landing gear. Records it
  // and returns true when the run ends.
  bool CheckCollision() {
    std::optional<Collision> collision;
    {
      const SectionTimer timer(&result_->timing.collision_s, &cpu().collision_s);
      collision = collision_checker_.Check(scene_, vehicle_.state(), previous_p_WB_);
      if (!collision && vehicle_.on_ground() && !was_on_ground_) {
        collision = collision_checker_.CheckTouchdown(vehicle_.state().p_WB,
                                                      vehicle_.last_touchdown_speed_mps(),
                                                      vehicle_.last_touchdown_tilt_rad());
      }
    }
    if (!collision) return false;
    result_->outcome = SitlResult::Outcome::kCollision;
    result_->collision = collision;
    result_->reason = "collision: " + collision->part + " with '" + collision->object_name + "'";
    if (result_->trajectory.back().t_s != vehicle_.state().t_s) {
      result_->trajectory.push_back(vehicle_.state());
    }
    return true;
  }

  // The ground truth of t_s - estimate_latency_s: the latest recorded state not newer than that
  // (the first state until then). Older states are dropped.
  const control::QuadState& EstimatedState(double t_s) {
    if (p_.estimate_latency_s <= 0.0) return vehicle_.state();
    const double due_s = DueTime(t_s - p_.estimate_latency_s);
    while (estimate_history_.size() > 1 && estimate_history_[1].t_s <= due_s) {
      estimate_history_.pop_front();
    }
    return estimate_history_.front();
  }

  // Rounding of accumulated times must not push a delivery to the next step.
  static double DueTime(double t_s) { return t_s + 1e-9; }

  const SitlRunnerParams& p_;
  const Scene* scene_;
  RayCaster* ray_caster_;
  perception::Autopilot* autopilot_;
  const SitlHooks& hooks_;
  SitlResult* result_;
  const double dt_s_;
  const long steps_;

  QuadrotorDynamics vehicle_;
  const control::RotorParameters controller_rotor_;  // the flight controller's thrust map
  SimulatedFlightController flight_controller_;
  Disturbances disturbances_;
  ImuSensor imu_;
  RangeSensor range_;
  CollisionChecker collision_checker_;
  SampleSchedule control_schedule_;
  SampleSchedule flight_controller_schedule_;
  std::mt19937_64 drop_rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  std::vector<CameraRuntime> cameras_;
  PoseHistory history_;
  const bool wants_ground_truth_;

  std::vector<perception::ImuSample> imu_samples_;  // taken in this step, delivered in step 2
  std::deque<std::pair<double, perception::RangeReading>> range_in_flight_;
  std::deque<std::pair<double, perception::AutopilotCommand>> commands_in_flight_;
  std::deque<std::pair<double, Eigen::Vector4d>> motor_commands_in_flight_;  // ESC delay
  std::deque<control::QuadState> estimate_history_;  // for estimate_latency_s > 0
  control::RotorThrustCommand rotor_thrusts_;
  Eigen::Vector3d previous_p_WB_ = Eigen::Vector3d::Zero();  // before the last vehicle step
  bool was_on_ground_ = false;
};

}  // namespace

SitlResult SitlRunner::Run(perception::Autopilot& autopilot, const SitlHooks& hooks) {
  const Clock::time_point wall_start = Clock::now();
  const double cpu_start_s = ProcessCpuSeconds();
  SitlResult result;
  result.autopilot_name = autopilot.name();
  {
    const RenderProfileScope render_profile(&result.timing.cpu.render);
    SitlFlight(params_, scene_, &ray_caster_, &autopilot, hooks, &result).Fly();
  }
  result.timing.cpu.total_s = ProcessCpuSeconds() - cpu_start_s;
  result.timing.wall_time_s = SecondsSince(wall_start);
  result.real_time_factor =
      result.timing.wall_time_s > 0.0 ? result.sim_time_s / result.timing.wall_time_s : 0.0;
  return result;
}

}  // namespace aperture::sim
