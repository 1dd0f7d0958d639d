// Cost of the high-level control step: the flatness map (F.6)-(F.30) on one reference sample,
// the full position/attitude controller (F.31)-(F.38), (B.10)-(B.20) (which includes one flatness
// evaluation), and one analytic reference sample. Targets: < 1 us each (55 Hz in the thesis,
// but the SITL runs it at the IMU rate).
#include <benchmark/benchmark.h>

#include <vector>

#include "control/flatness.h"
#include "control/position_controller.h"
#include "control/reference_trajectories.h"

namespace aperture::control {
namespace {

VehicleParameters DragVehicle() {
  VehicleParameters vehicle;
  vehicle.rotor_drag_D_per_s = Eigen::Vector3d(0.544, 0.386, 0.0);
  vehicle.thrust_velocity_coeff_kh = 0.009;
  return vehicle;
}

// 256 samples of one lemniscate loop, cycled so branch prediction sees varied inputs.
std::vector<TrajectoryPoint> Samples() {
  const LemniscateTrajectory lemniscate;
  std::vector<TrajectoryPoint> samples;
  for (int i = 0; i < 256; ++i) samples.push_back(lemniscate.Evaluate(3.0 + i * 0.0174));
  return samples;
}

void BM_Flatness(benchmark::State& state) {
  const VehicleParameters vehicle = DragVehicle();
  const std::vector<TrajectoryPoint> samples = Samples();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ComputeFlatnessOutputs(samples[i++ & 255], vehicle));
  }
}
BENCHMARK(BM_Flatness);

void BM_PositionControllerStep(benchmark::State& state) {
  const VehicleParameters vehicle = DragVehicle();
  const PositionController controller(vehicle);
  const std::vector<TrajectoryPoint> samples = Samples();
  std::vector<QuadState> states;
  for (const TrajectoryPoint& ref : samples) {
    QuadState s;
    s.p_WB = ref.p_W + Eigen::Vector3d(0.05, -0.03, 0.02);
    s.v_W = ref.v_W + Eigen::Vector3d(-0.1, 0.2, 0.0);
    s.q_WB = ComputeFlatnessOutputs(ref, vehicle).q_WB *
             Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
    states.push_back(s);
  }
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 255;
    benchmark::DoNotOptimize(controller.Compute(states[k], samples[k]));
  }
}
BENCHMARK(BM_PositionControllerStep);

void BM_LemniscateEvaluate(benchmark::State& state) {
  const LemniscateTrajectory lemniscate;
  double t = 3.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lemniscate.Evaluate(t));
    t += 1e-3;
  }
}
BENCHMARK(BM_LemniscateEvaluate);

}  // namespace
}  // namespace aperture::control
