// Cost of the per-IMU-sample recovery chain of Faessler thesis paper B at 500 Hz: the attitude
// estimator (B.22)-(B.26), the height filter (B.27)-(B.28), the launch detector (B.29) and one
// recovery state-machine step (B.3.2) in the attitude stage and in the position stage (which runs
// the full position controller). Targets: well under the 2 ms IMU period (< 1 us each).
#include <benchmark/benchmark.h>

#include <cmath>

#include "control/height_filter.h"
#include "control/imu_attitude_estimator.h"
#include "control/launch_detector.h"
#include "control/recovery_state_machine.h"

namespace aperture::control {
namespace {

constexpr double kDt = 0.002;

void BM_ImuAttitudeEstimator(benchmark::State& state) {
  ImuAttitudeEstimator estimator;
  estimator.Reset(Eigen::Quaterniond::Identity());
  // Gate open (slow rotation, |f| = g): prediction and correction both run.
  const Eigen::Vector3d f_B(0.3, -0.2, 9.8), omega_B(0.1, -0.2, 0.05);
  double t = 0.0;
  for (auto _ : state) {
    t += kDt;
    benchmark::DoNotOptimize(estimator.AddImu(t, f_B, omega_B));
  }
}
BENCHMARK(BM_ImuAttitudeEstimator);

void BM_HeightFilterPredictUpdate(benchmark::State& state) {
  HeightFilter filter;
  filter.Initialize(1.0);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d f_B(0.0, 0.5, 9.9);
  for (auto _ : state) {
    filter.Predict(kDt, HeightFilter::VerticalAcceleration(q, f_B, 9.81));
    filter.Update(*HeightFilter::HeightFromRange(1.0, q));
    benchmark::DoNotOptimize(filter.estimate());
  }
}
BENCHMARK(BM_HeightFilterPredictUpdate);

void BM_LaunchDetector(benchmark::State& state) {
  LaunchDetector detector;
  const Eigen::Vector3d f_B(0.1, 0.0, 9.81);
  double t = 0.0;
  for (auto _ : state) {
    t += kDt;
    benchmark::DoNotOptimize(detector.AddSample(t, f_B));
  }
}
BENCHMARK(BM_LaunchDetector);

void BM_RecoveryStepPositionStage(benchmark::State& state) {
  RecoveryStateMachine machine{VehicleParameters()};
  RecoveryInputs in;
  in.launch_detected = true;
  in.height = HeightEstimate{1.0, 0.0, 1.0};
  QuadState vision;
  vision.p_WB = Eigen::Vector3d(0.0, 0.0, 1.0);
  in.vision_state = vision;
  double t = 0.0;
  while (machine.stage() != RecoveryStage::kPosition) {
    in.t_s = (t += kDt);
    machine.Step(in);
  }
  in.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  for (auto _ : state) {
    in.t_s = (t += kDt);
    benchmark::DoNotOptimize(machine.Step(in));
  }
}
BENCHMARK(BM_RecoveryStepPositionStage);

// Attitude stage held by a large tilt (its exit needs < 20 deg).

void BM_RecoveryStepAttitudeStage(benchmark::State& state) {
  RecoveryStateMachine machine{VehicleParameters()};
  RecoveryInputs in;
  in.launch_detected = true;
  in.t_s = kDt;
  machine.Step(in);  // -> attitude stage
  in.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, 1, 0).normalized()));
  double t = kDt;
  for (auto _ : state) {
    in.t_s = (t += kDt);
    benchmark::DoNotOptimize(machine.Step(in));
  }
}
BENCHMARK(BM_RecoveryStepAttitudeStage);

}  // namespace
}  // namespace aperture::control
