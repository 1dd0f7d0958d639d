// Low-level control costs per control step (Faessler thesis Table G.3 reports, on the PX4
// micro controller, 1.4 us for a one-shot mix and 413 us for iterative mixing + saturation).
// Inputs cycle through 256 pre-drawn requests (fixed seed) so branch prediction sees variety.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "control/care_solver.h"
#include "control/low_level_controller.h"
#include "control/lqr_body_rate_controller.h"
#include "control/mixer.h"
#include "control/proportional_body_rate_controller.h"
#include "control/rotor_thrust_estimator.h"

namespace aperture::control {
namespace {

struct Request {
  Eigen::Vector3d torque_B;
  double thrust_mps2;
  Eigen::Vector3d omega_B;
};

// scale 1: unsaturated requests around hover; scale 4: most requests saturate.
std::vector<Request> Requests(double scale) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Request> requests(256);
  for (auto& r : requests) {
    r.torque_B = scale * Eigen::Vector3d(0.08 * u(rng), 0.08 * u(rng), 0.01 * u(rng));
    r.thrust_mps2 = 9.81 + 2.0 * scale * u(rng);
    r.omega_B = Eigen::Vector3d(u(rng), u(rng), u(rng));
  }
  return requests;
}

void BM_LqrBodyRateStep(benchmark::State& state) {
  const VehicleParameters vehicle;
  const LqrBodyRateController lqr(vehicle);
  RotorThrustEstimator estimator(vehicle);
  const std::vector<Request> requests = Requests(1.0);
  ThrustRatesCommand command;
  command.omega_des_B = Eigen::Vector3d(1.0, -0.5, 0.3);
  RotorThrustCommand thrusts;
  thrusts.thrust_N.setConstant(1.1);
  size_t i = 0;
  for (auto _ : state) {
    const Request& r = requests[i++ & 255];
    // One control step without the mixer: estimate, LQR law (G.12), estimator update (G.7).
    const Eigen::Vector3d torque = lqr.ComputeTorque(command, r.omega_B, estimator.BodyTorque_B());
    thrusts.thrust_N[0] = 1.1 + 0.1 * torque.x();
    estimator.Propagate(thrusts, 0.001);
    benchmark::DoNotOptimize(torque);
  }
}
BENCHMARK(BM_LqrBodyRateStep);

void BM_LqrControlLawOnly(benchmark::State& state) {
  const LqrBodyRateController lqr{VehicleParameters()};
  const std::vector<Request> requests = Requests(1.0);
  ThrustRatesCommand command;
  command.omega_des_B = Eigen::Vector3d(1.0, -0.5, 0.3);
  size_t i = 0;
  for (auto _ : state) {
    const Request& r = requests[i++ & 255];
    benchmark::DoNotOptimize(lqr.ComputeTorque(command, r.omega_B, r.torque_B));
  }
}
BENCHMARK(BM_LqrControlLawOnly);

void BM_ProportionalControlLaw(benchmark::State& state) {
  const ProportionalBodyRateController p{VehicleParameters()};
  const std::vector<Request> requests = Requests(1.0);
  size_t i = 0;
  for (auto _ : state) {
    const Request& r = requests[i++ & 255];
    benchmark::DoNotOptimize(p.ComputeTorque(Eigen::Vector3d(1.0, -0.5, 0.3), r.omega_B));
  }
}
BENCHMARK(BM_ProportionalControlLaw);

// range(0): mixing (0 iterative, 1 one-shot); range(1): saturation (0 prioritized, 1 clip);
// range(2): request scale (1 unsaturated, 4 mostly saturated).
void BM_Mixer(benchmark::State& state) {
  MixerParameters params;
  params.mixing =
      state.range(0) == 0 ? MixerParameters::Mixing::kIterative : MixerParameters::Mixing::kOneShot;
  params.saturation = state.range(1) == 0 ? MixerParameters::Saturation::kPrioritized
                                          : MixerParameters::Saturation::kClip;
  const Mixer mixer(VehicleParameters(), params);
  const std::vector<Request> requests = Requests(static_cast<double>(state.range(2)));
  size_t i = 0;
  long iterations = 0, saturated = 0;
  for (auto _ : state) {
    const Request& r = requests[i++ & 255];
    const MixerResult result = mixer.Mix(r.torque_B, r.thrust_mps2);
    iterations += result.iterations;
    saturated +=
        result.yaw_torque_saturated || result.collective_thrust_saturated || result.clipped;
    benchmark::DoNotOptimize(result);
  }
  state.counters["solves_per_mix"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
  state.counters["saturated_fraction"] =
      benchmark::Counter(static_cast<double>(saturated), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_Mixer)
    ->ArgNames({"one_shot", "clip", "scale"})
    ->Args({0, 0, 1})
    ->Args({1, 0, 1})
    ->Args({1, 1, 1})
    ->Args({0, 0, 4})
    ->Args({1, 1, 4});

// Whole flight-controller step: LQR (G.12) + iterative mixer + saturation + motor commands +
// thrust-estimator update.
void BM_LowLevelControllerStep(benchmark::State& state) {
  const VehicleParameters vehicle;
  LowLevelController controller(vehicle);
  const std::vector<Request> requests = Requests(1.0);
  ThrustRatesCommand command;
  command.collective_thrust_mps2 = 9.81;
  command.omega_des_B = Eigen::Vector3d(1.0, -0.5, 0.3);
  size_t i = 0;
  for (auto _ : state) {
    const Request& r = requests[i++ & 255];
    benchmark::DoNotOptimize(controller.Step(command, r.omega_B, 0.001));
  }
}
BENCHMARK(BM_LowLevelControllerStep);

void BM_CareBodyRate(benchmark::State& state) {
  const VehicleParameters vehicle;
  const BodyRateLinearModel model = BuildBodyRateLinearModel(vehicle);
  const Eigen::MatrixXd Q = LqrBodyRateParameters().state_weights.asDiagonal();
  const Eigen::MatrixXd R = Eigen::MatrixXd::Identity(3, 3);
  double residual = 0.0;
  for (auto _ : state) {
    const CareResult result = SolveContinuousAlgebraicRiccati(model.A, model.B, Q, R);
    residual = result.residual;
    benchmark::DoNotOptimize(result);
  }
  state.counters["residual"] = residual;
}
BENCHMARK(BM_CareBodyRate)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::control
