#include "sim/sitl/sitl_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/sensors/sample_schedule.h"

namespace aperture::sim {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void RequirePositive(double value, const std::string& field) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument("SitlRunnerParams." + field + " = " + std::to_string(value) +
                                " must be positive and finite");
  }
}

void RequireNonNegative(double value, const std::string& field) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument("SitlRunnerParams." + field + " = " + std::to_string(value) +
                                " must be >= 0 and finite");
  }
}

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
  RequirePositive(duration_s, "duration_s");
  RequirePositive(dynamics_rate_hz, "dynamics_rate_hz");
  RequirePositive(control_rate_hz, "control_rate_hz");
  RequireNonNegative(command_latency_s, "command_latency_s");
  RequireNonNegative(range_latency_s, "range_latency_s");
  dynamics.Validate();
  disturbances.Validate();
  flight_controller.Validate();
  imu.Validate();
  range.Validate();
  CollisionChecker::Validate(dynamics, collision);  // both, and the landing gear against the body
  // Sensors and controllers sample once per dynamics step at most (sample_schedule.h).
  const double fastest =
      std::max({flight_controller.rate_hz, imu.rate_hz, control_rate_hz, range.rate_hz});
  if (dynamics_rate_hz < fastest * (1.0 - 1e-9)) {
    throw std::invalid_argument(
        "SitlRunnerParams.dynamics_rate_hz = " + std::to_string(dynamics_rate_hz) +
        " is below the fastest flight-controller / IMU / control / range rate " +
        std::to_string(fastest) + "; raise it");
  }
  if (trajectory_decimation < 1) {
    throw std::invalid_argument("SitlRunnerParams.trajectory_decimation must be >= 1");
  }
  for (size_t i = 0; i < cameras.size(); ++i) {
    const SitlCamera& c = cameras[i];
    const std::string field = "cameras[" + std::to_string(i) + "] ('" + c.name + "').";
    if (!c.model) throw std::invalid_argument("SitlRunnerParams." + field + "model is missing");
    RequirePositive(c.rate_hz, field + "rate_hz");
    RequireNonNegative(c.latency_s, field + "latency_s");
    if (!(c.drop_probability >= 0.0 && c.drop_probability < 1.0)) {
      throw std::invalid_argument("SitlRunnerParams." + field + "drop_probability = " +
                                  std::to_string(c.drop_probability) + " must be in [0, 1)");
    }
    if (c.rate_hz > dynamics_rate_hz) {
      throw std::invalid_argument("SitlRunnerParams." + field + "rate_hz exceeds dynamics_rate_hz");
    }
    if (!c.T_BC.matrix().allFinite() || (c.T_WC_fixed && !c.T_WC_fixed->matrix().allFinite())) {
      throw std::invalid_argument("SitlRunnerParams." + field + "T_BC / T_WC_fixed is not finite");
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

SitlResult SitlRunner::Run(perception::Autopilot& autopilot, const SitlHooks& hooks) {
  const Clock::time_point wall_start = Clock::now();
  SitlResult result;
  result.autopilot_name = autopilot.name();
  const SitlRunnerParams& p = params_;
  const control::VehicleParameters& vehicle_params = p.dynamics.vehicle;
  const double dt_s = 1.0 / p.dynamics_rate_hz;
  const long steps = std::lround(p.duration_s * p.dynamics_rate_hz);

  control::QuadState initial = p.initial_state;
  initial.t_s = 0.0;
  QuadrotorDynamics vehicle(p.dynamics, initial);
  SimulatedFlightController flight_controller(vehicle_params, p.flight_controller);
  if (p.start_hovering) {
    control::RotorThrustCommand hover;
    hover.thrust_N.setConstant(vehicle_params.mass_kg * vehicle_params.gravity_mps2 / 4.0);
    vehicle.SetRotorThrustCommand(hover);
    vehicle.SettleRotors();
    flight_controller.ResetThrustEstimate(vehicle.RotorThrusts_N());
  } else {
    flight_controller.ResetThrustEstimate(vehicle.RotorThrusts_N());
  }
  Disturbances disturbances(p.disturbances);
  ImuSensor imu(p.imu);
  // The range ray sees what the vehicle can collide with: the ground and the scene's objects
  // except the collision checker's ignored ones (the parts attached to the body).
  RangeWorld range_world{p.dynamics.ground_height_m, scene_, {}};
  for (const std::string& name : p.collision.ignored_objects) {
    const int id = scene_ != nullptr ? scene_->FindId(name) : -1;
    if (id >= 0) range_world.see_through_object_ids.push_back(id);
  }
  RangeSensor range(p.range, std::move(range_world));
  CollisionChecker collision_checker(p.dynamics, p.collision);
  SampleSchedule control_schedule(p.control_rate_hz);
  SampleSchedule flight_controller_schedule(p.flight_controller.rate_hz);
  std::mt19937_64 drop_rng(p.drop_seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  std::vector<CameraRuntime> cameras;
  double max_exposure_s = 0.0;
  for (const SitlCamera& camera : p.cameras) {
    cameras.push_back(CameraRuntime{&camera,
                                    CameraEffects(camera.effects),
                                    nullptr,
                                    SampleSchedule(camera.rate_hz),
                                    {},
                                    0,
                                    {}});
    if (camera.T_WC_fixed && p.reuse_fixed_camera_background) {
      cameras.back().fixed =
          std::make_unique<FixedCameraRenderer>(*camera.model, *camera.T_WC_fixed);
    }
    cameras.back().stats.name = camera.name;
    max_exposure_s = std::max(max_exposure_s, camera.effects.exposure_s);
  }
  PoseHistory history(max_exposure_s + 2.0 * dt_s);
  std::deque<std::pair<double, perception::RangeReading>> range_in_flight;
  std::deque<std::pair<double, perception::AutopilotCommand>> commands_in_flight;
  perception::AutopilotCommand last_command;
  control::RotorThrustCommand rotor_thrusts;
  rotor_thrusts.thrust_N = vehicle.RotorThrusts_N();
  const bool wants_ground_truth = autopilot.UsesGroundTruth();

  result.trajectory.push_back(vehicle.state());
  history.Add(vehicle.state());
  for (long k = 0;; ++k) {
    const double t_s = k * dt_s;
    // 1. sensors.
    Clock::time_point section = Clock::now();
    const control::QuadState& state = vehicle.state();
    const std::vector<perception::ImuSample> imu_samples =
        imu.Update(t_s, vehicle.SpecificForce_B(), state.omega_B);
    if (p.range_enabled) {
      if (const std::optional<perception::RangeReading> reading = range.Update(state)) {
        range_in_flight.emplace_back(t_s + p.range_latency_s, *reading);
      }
    }
    result.timing.dynamics_s += SecondsSince(section);
    section = Clock::now();
    double hooks_s = 0.0;  // inside this section, booked apart from rendering
    for (size_t c = 0; c < cameras.size(); ++c) {
      CameraRuntime& runtime = cameras[c];
      if (!runtime.schedule.Due(t_s)) continue;
      const int slot = runtime.slot++;
      ++runtime.stats.frames_due;
      const SitlCamera& camera = *runtime.camera;
      if (camera.drop_probability > 0.0 && uniform(drop_rng) < camera.drop_probability) {
        ++runtime.stats.frames_dropped;
        continue;
      }
      if (hooks.before_render) {
        const Clock::time_point hook_start = Clock::now();
        hooks.before_render(t_s, state);
        hooks_s += SecondsSince(hook_start);
      }
      const Eigen::Isometry3d T_BC = camera.T_BC;
      const std::optional<Eigen::Isometry3d>& T_WC_fixed = camera.T_WC_fixed;
      const auto T_WC_at = [&history, &T_BC, &T_WC_fixed](double t) {
        return T_WC_fixed ? *T_WC_fixed : Eigen::Isometry3d(history.T_WB(t) * T_BC);
      };
      const double t_mid_s = t_s - 0.5 * camera.effects.exposure_s;
      CapturedFrame captured =
          runtime.fixed
              ? runtime.effects.Capture(
                    [&](const Eigen::Isometry3d&, const RenderOptions& options, RenderOutput* out) {
                      runtime.fixed->Render(*scene_, options, out);
                    },
                    T_WC_at, t_mid_s, slot, camera.render)
              : runtime.effects.Capture(ray_caster_, *scene_, *camera.model, T_WC_at, t_mid_s, slot,
                                        camera.render);
      captured.frame.camera_id = static_cast<int>(c);
      if (hooks.on_frame) {
        const Clock::time_point hook_start = Clock::now();
        hooks.on_frame(static_cast<int>(c), captured, state);
        hooks_s += SecondsSince(hook_start);
      }
      runtime.in_flight.emplace_back(t_s + camera.latency_s, captured.frame);
    }
    result.timing.render_s += SecondsSince(section) - hooks_s;
    result.timing.hooks_s += hooks_s;

    // 2. deliveries.
    section = Clock::now();
    for (const perception::ImuSample& sample : imu_samples) {
      flight_controller.SetGyro(sample.omega_B);
      autopilot.OnImu(sample);
      result.imu.push_back(sample);
    }
    // Rounding of accumulated times must not push a delivery to the next step.
    const double due_s = t_s + 1e-9;
    while (!range_in_flight.empty() && range_in_flight.front().first <= due_s) {
      autopilot.OnRange(range_in_flight.front().second);
      result.range.push_back(range_in_flight.front().second);
      range_in_flight.pop_front();
    }
    for (CameraRuntime& runtime : cameras) {
      while (!runtime.in_flight.empty() && runtime.in_flight.front().first <= due_s) {
        autopilot.OnFrame(runtime.in_flight.front().second);
        ++runtime.stats.frames_delivered;
        runtime.in_flight.pop_front();
      }
    }

    // 3. high-level control.
    bool done = false;
    if (control_schedule.Due(t_s)) {
      if (wants_ground_truth) autopilot.OnGroundTruth(state);
      const perception::AutopilotCommand command = autopilot.Step(t_s);
      commands_in_flight.emplace_back(t_s + p.command_latency_s, command);
      result.commands.push_back(SitlCommandRecord{t_s, command, rotor_thrusts.thrust_N});
      done = command.done;
    }
    result.timing.autopilot_s += SecondsSince(section);
    if (done) {
      result.outcome = SitlResult::Outcome::kAutopilotDone;
      result.reason = "autopilot done: " + autopilot.status();
      break;
    }
    if (k >= steps) {
      result.outcome = SitlResult::Outcome::kDurationReached;
      result.reason = "duration reached";
      break;
    }

    // 4.-5. flight controller and vehicle.
    section = Clock::now();
    while (!commands_in_flight.empty() && commands_in_flight.front().first <= due_s) {
      flight_controller.SetCommand(commands_in_flight.front().second);
      commands_in_flight.pop_front();
    }
    if (flight_controller_schedule.Due(t_s)) {
      rotor_thrusts = flight_controller.Step();
      vehicle.SetRotorThrustCommand(rotor_thrusts);
    }
    const Eigen::Vector3d previous_p_WB = vehicle.state().p_WB;
    const bool was_on_ground = vehicle.on_ground();
    disturbances.StepVehicle(dt_s, &vehicle);
    if (!vehicle.state().IsValid()) {
      throw std::runtime_error("SitlRunner: the vehicle state became invalid at t = " +
                               std::to_string(t_s) + " s (check the autopilot's commands)");
    }
    history.Add(vehicle.state());
    if ((k + 1) % p.trajectory_decimation == 0) result.trajectory.push_back(vehicle.state());
    result.timing.dynamics_s += SecondsSince(section);

    // 6. collisions.
    section = Clock::now();
    std::optional<Collision> collision =
        collision_checker.Check(scene_, vehicle.state(), previous_p_WB);
    if (!collision && vehicle.on_ground() && !was_on_ground) {
      collision =
          collision_checker.CheckTouchdown(vehicle.state().p_WB, vehicle.last_touchdown_speed_mps(),
                                           vehicle.last_touchdown_tilt_rad());
    }
    result.timing.collision_s += SecondsSince(section);
    if (collision) {
      result.outcome = SitlResult::Outcome::kCollision;
      result.collision = collision;
      result.reason = "collision: " + collision->part + " with '" + collision->object_name + "'";
      if (result.trajectory.back().t_s != vehicle.state().t_s) {
        result.trajectory.push_back(vehicle.state());
      }
      break;
    }
  }
  result.sim_time_s = vehicle.state().t_s;
  result.autopilot_status = autopilot.status();
  for (const CameraRuntime& runtime : cameras) result.cameras.push_back(runtime.stats);
  result.timing.wall_time_s = SecondsSince(wall_start);
  result.real_time_factor =
      result.timing.wall_time_s > 0.0 ? result.sim_time_s / result.timing.wall_time_s : 0.0;
  return result;
}

}  // namespace aperture::sim
