#include "experiments/control/recovery_section.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "control/recovery_pipeline.h"
#include "output/svg_plot.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/simulated_flight_controller.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::experiments {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDynamicsStep_s = 0.001;  // vehicle and flight controller at 1 kHz
constexpr int kRecoveryDecimation = 2;     // recovery pipeline at 500 Hz (B.2.5)
constexpr double kHoldTime_s = 0.4;        // in the hand before the release
constexpr double kTimeLimit_s = 6.0;       // release -> end of the flight
constexpr double kVisionDelay_s = 1.0;     // height stage -> vision estimate available
// Stable hover at the end of the flight.
constexpr double kMaxFinalTilt_rad = 3.0 * kPi / 180.0;
constexpr double kMaxFinalSpeed_mps = 0.1;
constexpr double kMaxFinalRate_radps = 0.2;

struct Throw {
  Eigen::Vector3d p_W;              // release position [m]
  Eigen::Quaterniond q_WB;          // attitude in the hand
  Eigen::Vector3d v_W_mps;          // release velocity
  Eigen::Vector3d omega_B_radps;    // release body rates
};

// Uniform rotation (Shoemake) and direction, from `rng` so every throw follows from its seed.
Eigen::Quaterniond RandomRotation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = 2.0 * kPi * u(rng), u3 = 2.0 * kPi * u(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
}
Eigen::Vector3d RandomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d d(n(rng), n(rng), n(rng));
  return d.normalized();
}

Throw RandomThrow(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Throw t;
  t.p_W = Eigen::Vector3d(0.0, 0.0, 1.2 + 0.6 * u(rng));
  t.q_WB = RandomRotation(rng);
  const double heading = 2.0 * kPi * u(rng);
  const double horizontal_mps = 4.0 * u(rng);
  t.v_W_mps = Eigen::Vector3d(horizontal_mps * std::cos(heading), horizontal_mps * std::sin(heading),
                              -1.0 + 5.0 * u(rng));
  t.omega_B_radps = 14.0 * u(rng) * RandomDirection(rng);
  return t;
}

double Heading(const Eigen::Quaterniond& q_WB) {
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}
double Tilt(const Eigen::Quaterniond& q_WB) {
  return std::acos(std::clamp((q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
}

struct ThrowOutcome {
  bool success = false;
  bool crashed = false;
  double held_tilt_rad = 0.0;
  double release_speed_mps = 0.0;
  double release_rate_radps = 0.0;
  std::optional<double> recovery_time_s;  // release -> position stage
  double min_height_m = 1e9;
  double end_time_s = 0.0;  // since release: crash or end of the flight
};

ThrowOutcome FlyThrow(const Throw& t, std::uint64_t seed) {
  sim::QuadrotorDynamicsParams dynamics_params;  // the bench vehicle
  const control::VehicleParameters& vehicle = dynamics_params.vehicle;
  control::QuadState held;
  held.p_WB = t.p_W;
  held.q_WB = t.q_WB;
  sim::QuadrotorDynamics dynamics(dynamics_params, held);
  sim::ImuSensorParams imu_params;
  imu_params.seed = seed;
  sim::ImuSensor imu(imu_params);
  sim::RangeSensorParams range_params;
  range_params.seed = seed + 1;
  sim::RangeSensor range(range_params);
  sim::SimulatedFlightController flight_controller(vehicle);
  flight_controller.ResetThrustEstimate(dynamics.RotorThrusts_N());
  control::RecoveryPipeline recovery(vehicle);
  const sim::CollisionChecker collision(vehicle, sim::CollisionParams{});
  const Eigen::Vector3d vision_offset_V(0.7, -1.3, 0.05);  // origin of W in V

  ThrowOutcome outcome;
  outcome.held_tilt_rad = Tilt(t.q_WB);
  outcome.release_speed_mps = t.v_W_mps.norm();
  outcome.release_rate_radps = t.omega_B_radps.norm();
  bool released = false;
  std::optional<Eigen::Matrix3d> R_VW;  // vision frame, once the vision pipeline is initialized
  const long steps = std::lround((kHoldTime_s + kTimeLimit_s) / kDynamicsStep_s);
  for (long k = 1; k <= steps; ++k) {
    const double t_s = k * kDynamicsStep_s;
    if (!released && t_s >= kHoldTime_s - 1e-9) {
      released = true;
      dynamics.ApplyImpulse(vehicle.mass_kg * t.v_W_mps, vehicle.Inertia() * t.omega_B_radps);
    }
    if (!released) {  // in the hand: still, on the simulator clock
      held.t_s = t_s;
      dynamics.SetState(held);
    }
    const control::QuadState& truth = dynamics.state();
    const Eigen::Vector3d f_B =
        released ? dynamics.SpecificForce_B()
                 : Eigen::Vector3d(truth.q_WB.conjugate() *
                                   Eigen::Vector3d(0.0, 0.0, vehicle.gravity_mps2));
    for (const perception::ImuSample& sample : imu.Update(t_s, f_B, truth.omega_B)) {
      recovery.AddImu(sample.t_s, sample.specific_force_B, sample.omega_B);
      flight_controller.SetGyro(sample.omega_B);
    }
    if (const auto reading = range.Update(truth); reading && reading->valid) {
      recovery.AddRange(reading->range_m);
    }
    if (k % kRecoveryDecimation == 0) {
      const control::RecoveryStateMachine& machine = recovery.state_machine();
      if (!R_VW && machine.stage() == control::RecoveryStage::kHeight &&
          t_s - machine.stage_entry_time_s() >= kVisionDelay_s - 1e-9) {
        // The visual odometry initializes its gravity-aligned frame V from the on-board attitude
        // estimate (B.2.5), so V shares the estimator's heading, not the world's.
        const double heading_offset_rad =
            Heading(recovery.attitude().q_WB()) - Heading(truth.q_WB);
        R_VW = Eigen::AngleAxisd(heading_offset_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      }
      if (R_VW) {
        control::QuadState vision = truth;
        vision.p_WB = *R_VW * truth.p_WB + vision_offset_V;
        vision.v_W = *R_VW * truth.v_W;
        vision.q_WB = Eigen::Quaterniond(*R_VW) * truth.q_WB;
        recovery.SetVisionState(vision);
      }
      const control::RecoveryOutput out = recovery.Step(t_s);
      perception::AutopilotCommand command;
      command.kind = perception::AutopilotCommand::Kind::kThrustRates;
      command.thrust_rates = out.command;
      flight_controller.SetCommand(command);
      if (out.stage == control::RecoveryStage::kPosition && !outcome.recovery_time_s) {
        outcome.recovery_time_s = t_s - kHoldTime_s;
      }
    }
    dynamics.SetRotorThrustCommand(flight_controller.Step());
    if (!released) continue;
    const Eigen::Vector3d previous_p_WB = dynamics.state().p_WB;
    dynamics.Step(kDynamicsStep_s);
    outcome.min_height_m = std::min(outcome.min_height_m, dynamics.state().p_WB.z());
    outcome.end_time_s = t_s - kHoldTime_s;
    if (collision.Check(nullptr, dynamics.state(), previous_p_WB)) {
      outcome.crashed = true;
      return outcome;
    }
  }
  const control::QuadState& end = dynamics.state();
  outcome.success = recovery.state_machine().stage() == control::RecoveryStage::kPosition &&
                    Tilt(end.q_WB) < kMaxFinalTilt_rad && end.v_W.norm() < kMaxFinalSpeed_mps &&
                    end.omega_B.norm() < kMaxFinalRate_radps;
  return outcome;
}

void RunRecovery(const ControlBenchOptions& options, nlohmann::json* summary,
                 output::HtmlReport* report) {
  const int trials =
      options.quick ? std::min(options.recovery_trials, 10) : options.recovery_trials;
  std::vector<ThrowOutcome> outcomes(static_cast<size_t>(std::max(trials, 0)));
  tbb::parallel_for(tbb::blocked_range<int>(0, trials), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i < range.end(); ++i) {
      const std::uint64_t seed = options.seed * 1000003 + static_cast<std::uint64_t>(i);
      std::mt19937_64 rng(seed);
      outcomes[i] = FlyThrow(RandomThrow(rng), seed);
    }
  });

  int successes = 0, crashes = 0;
  double min_height_m = 1e9;
  std::vector<double> times_s, ok_tilt_deg, ok_time_s, failed_tilt_deg, failed_time_s;
  for (const ThrowOutcome& o : outcomes) {
    successes += o.success ? 1 : 0;
    crashes += o.crashed ? 1 : 0;
    min_height_m = std::min(min_height_m, o.min_height_m);
    const double tilt_deg = o.held_tilt_rad * 180.0 / kPi;
    if (o.success) {
      times_s.push_back(*o.recovery_time_s);
      ok_tilt_deg.push_back(tilt_deg);
      ok_time_s.push_back(*o.recovery_time_s);
    } else {
      failed_tilt_deg.push_back(tilt_deg);
      failed_time_s.push_back(o.end_time_s);
    }
  }
  nlohmann::json& out = (*summary)["recovery"];
  out["trials"] = trials;
  out["successes"] = successes;
  out["crashes"] = crashes;
  double sum_s = 0.0;
  for (double t : times_s) sum_s += t;
  out["time_mean"] = times_s.empty() ? 0.0 : sum_s / static_cast<double>(times_s.size());
  out["time_max"] = times_s.empty() ? 0.0 : *std::max_element(times_s.begin(), times_s.end());
  out["min_height"] = trials > 0 ? min_height_m : 0.0;

  report->AddSection("Throw recovery (paper B, B.4)");
  report->AddParagraph(
      "Random hand throws: any attitude in the hand, 0-4 m/s horizontal, -1 to +4 m/s vertical at "
      "release, body rates up to 14 rad/s; recovered from the IMU and range sensor alone (vision "
      "emulated 1 s after the height stage starts). Success: no ground contact and a stable "
      "hover in the position stage within 6 s of the release.");
  report->AddTable(out, "recovery figures (SI units)");
  report->AddSvg(output::SvgPlot::Histogram({"Time from release to position hold (successful)",
                                             "t [s]", "throws"},
                                            {{"recovery time", times_s}}),
                 "Recovery times");
  output::SvgPlot scatter({"Outcome by attitude in the hand", "tilt when thrown [deg]",
                           "recovery time / time of failure [s]"});
  scatter.AddScatter("success", ok_tilt_deg, ok_time_s);
  scatter.AddScatter("failure", failed_tilt_deg, failed_time_s);
  report->AddSvg(scatter.Render(), "Each throw: held tilt vs recovery time (failures: when they "
                                   "crashed or the time limit)");
}

}  // namespace

ControlBenchSection MakeRecoverySection() { return {"recovery", RunRecovery}; }

}  // namespace aperture::experiments
