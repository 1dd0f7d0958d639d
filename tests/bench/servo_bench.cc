// One step of each servo law (servo/): the moment servo on opening contours of 5 to 320 vertices
// (a tracked TS2P contour has ~100; the tag's outline 4), the four-point tag servo and the GapFlyt
// PID. A step is what runs per camera frame (30 Hz in the gapflyt scenario), so anything below
// ~1 ms leaves the frame budget to perception.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "perception/camera/optical_axes.h"
#include "servo/moment_servo.h"
#include "servo/pid_servo.h"
#include "servo/point_servo.h"

namespace aperture::servo {
namespace {

Eigen::Isometry3d ForwardMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = perception::OpticalAxesAlongX();
  return T_BC;
}

Eigen::Isometry3d DownwardMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() << 0, -1, 0, -1, 0, 0, 0, 0, -1;
  return T_BC;
}

// A star-like opening of `count` vertices (radius 0.2..0.3, elongated along x so its orientation
// is defined), shifted by `offset` in the normalized image.
std::vector<Eigen::Vector2d> Contour(int count, const Eigen::Vector2d& offset) {
  std::vector<Eigen::Vector2d> contour;
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * M_PI * i / count;
    const double radius = 0.25 + 0.05 * std::cos(3.0 * angle);
    contour.push_back(offset +
                      Eigen::Vector2d(1.4 * radius * std::cos(angle), radius * std::sin(angle)));
  }
  return contour;
}

void BM_MomentServoStep(benchmark::State& state, YawMode yaw) {
  const int count = static_cast<int>(state.range(0));
  MomentServoParams params;
  params.yaw = yaw;
  MomentServo servo(params, yaw == YawMode::kHold ? ForwardMount() : DownwardMount());
  servo.SetDesired(Contour(count, Eigen::Vector2d::Zero()), 2.0);
  const std::vector<std::vector<Eigen::Vector2d>> views = {
      Contour(count, Eigen::Vector2d(0.1, -0.05)), Contour(count, Eigen::Vector2d(0.08, -0.02))};
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(servo.Step(views[k++ % views.size()]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_MomentServoStep, yaw_hold, YawMode::kHold)->RangeMultiplier(4)->Range(5, 320);
BENCHMARK_CAPTURE(BM_MomentServoStep, yaw_orientation, YawMode::kOrientation)
    ->RangeMultiplier(4)
    ->Range(5, 320);

void BM_PointServoStep(benchmark::State& state) {
  PointServo servo(PointServoParams{}, DownwardMount());
  const PointServo::Corners desired = {Eigen::Vector2d(-0.1, -0.1), Eigen::Vector2d(0.1, -0.1),
                                       Eigen::Vector2d(0.1, 0.1), Eigen::Vector2d(-0.1, 0.1)};
  servo.SetDesired(desired, 2.0);
  PointServo::Corners current = desired;
  for (Eigen::Vector2d& corner : current) corner = 0.8 * corner + Eigen::Vector2d(0.05, 0.02);
  double t_s = 0.0;
  for (auto _ : state) {
    t_s += 1.0 / 30.0;
    benchmark::DoNotOptimize(servo.Step(t_s, current, 2.4));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PointServoStep);

void BM_PidServoStep(benchmark::State& state) {
  PidServo pid(PidServoParams{}, ForwardMount(), 0.5);
  double t_s = 0.0;
  for (auto _ : state) {
    t_s += 1.0 / 30.0;
    benchmark::DoNotOptimize(pid.Step(t_s, Eigen::Vector2d(0.05 * std::sin(t_s), 0.02)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PidServoStep);

}  // namespace
}  // namespace aperture::servo
