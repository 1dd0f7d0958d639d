// Cost of the pose + IMU ESKF (report only): one IMU propagation step (nominal + 15x15
// covariance), one pose update at the current time, and one pose update 50 ms late (update plus
// re-propagation of 25 IMU samples at 500 Hz).
#include <benchmark/benchmark.h>

#include <cmath>

#include "perception/estimation/pose_imu_filter.h"

namespace aperture::perception {
namespace {

constexpr double kImuDt = 0.002;  // 500 Hz

// A slowly rotating, tilted vehicle: non-trivial rates and specific force.
ImuSample SampleAt(double t_s) {
  ImuSample sample;
  sample.t_s = t_s;
  sample.specific_force_B = Eigen::Vector3d(0.5 * std::sin(t_s), 0.3 * std::cos(t_s), 9.81);
  sample.omega_B = Eigen::Vector3d(0.2 * std::cos(t_s), -0.1, 0.3);
  return sample;
}

PoseMeasurement PoseAt(const PoseImuFilter& filter, double t_s) {
  PoseMeasurement z;
  z.t_s = t_s;
  const PoseImuEstimate e = filter.Estimate();
  z.p_WX = e.state.p_WB + Eigen::Vector3d(0.01, -0.01, 0.005);
  z.q_WX = e.state.q_WB;
  z.covariance = Matrix6d::Identity() * 1e-4;
  return z;
}

// A filter that has run 1 s (full 0.5 s history).
PoseImuFilter WarmFilter(double* t_s) {
  PoseImuFilter filter(PoseImuFilterParams{}, control::QuadState{});
  for (*t_s = kImuDt; *t_s <= 1.0; *t_s += kImuDt) filter.Propagate(SampleAt(*t_s));
  return filter;
}

void BM_PoseImuFilterPropagate(benchmark::State& state) {
  double t = 0.0;
  PoseImuFilter filter = WarmFilter(&t);
  for (auto _ : state) {
    filter.Propagate(SampleAt(t));
    t += kImuDt;
  }
  benchmark::DoNotOptimize(filter.Estimate());
}
BENCHMARK(BM_PoseImuFilterPropagate);

// Update at the time of the latest IMU sample (no replay). One iteration = one propagation plus
// one update; subtract BM_PoseImuFilterPropagate for the update alone.
void BM_PoseImuFilterUpdateOnTime(benchmark::State& state) {
  double t = 0.0;
  PoseImuFilter filter = WarmFilter(&t);
  for (auto _ : state) {
    filter.Propagate(SampleAt(t));
    benchmark::DoNotOptimize(filter.Update(PoseAt(filter, t)));
    t += kImuDt;
  }
}
BENCHMARK(BM_PoseImuFilterUpdateOnTime);

// Poses at 31.25 Hz stamped 50 ms in the past: one iteration = 16 propagations plus one update
// that re-propagates 25 samples (re-applying the one or two later poses). Subtract 16 times
// BM_PoseImuFilterPropagate for the cost of the late update.
void BM_PoseImuFilterUpdateDelayed50ms(benchmark::State& state) {
  double t = 0.0;
  PoseImuFilter filter = WarmFilter(&t);
  for (auto _ : state) {
    for (int k = 0; k < 16; ++k, t += kImuDt) filter.Propagate(SampleAt(t));
    benchmark::DoNotOptimize(filter.Update(PoseAt(filter, t - kImuDt - 0.05)));
  }
}
BENCHMARK(BM_PoseImuFilterUpdateDelayed50ms);

}  // namespace
}  // namespace aperture::perception
