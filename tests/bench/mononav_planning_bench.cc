// Per-frame planning cost of the monocular forest navigation (seed 003 Sec. III-B to III-E) on a
// 40 x 30 patch depth map (the mono_depth grid of a 640x480 frame): ego-dynamic transform +
// back-projection + PCL clustering + binary program + spatial windows, and the minimum-time
// quintic B-spline (NLopt time scaling + refit) over a 10-point path. Target: planning <= 20 ms
// per frame on one core (issue 17).
#include <benchmark/benchmark.h>

#include <cmath>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "planning/mono_nav/ego_dynamic_space.h"
#include "planning/mono_nav/min_time_bspline.h"
#include "planning/mono_nav/waypoint_selector.h"

namespace aperture::planning {
namespace {

// Depth of a forest-like view: far background (30 m), ground rising to the bottom rows, and
// three trunks (columns) at 3, 6 and 9 m.
cv::Mat ForestDepth() {
  cv::Mat depth(30, 40, CV_32F, cv::Scalar(30.0f));
  for (int r = 16; r < 30; ++r) depth.row(r).setTo(1.5 * 15.0 / (r - 15 + 0.5));
  for (const auto& [column, distance] : {std::pair{18, 3.0f}, {6, 6.0f}, {30, 9.0f}}) {
    for (int c = column; c < column + 3; ++c) depth.col(c).rowRange(0, 20).setTo(distance);
  }
  return depth;
}

void BM_WaypointSelection40x30(benchmark::State& state) {
  const cv::Mat depth = ForestDepth();
  const perception::PinholeCamera camera(640, 480,
                                         perception::PinholeIntrinsics{320, 320, 319.5, 239.5});
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = perception::OpticalAxesAlongX();
  const EgoDynamicParams ego;
  const WaypointSelector selector;
  for (auto _ : state) {
    const cv::Mat d_eff = EgoDynamicTransform(depth, ego);
    benchmark::DoNotOptimize(
        selector.Select(BackProjectGrid(d_eff, Eigen::Vector2d(16, 16), camera, T_BC),
                        Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(20, 0, 0)));
  }
}
BENCHMARK(BM_WaypointSelection40x30)->Unit(benchmark::kMillisecond);

void BM_MinTimeBSpline10Points(benchmark::State& state) {
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 9; ++i) {
    const double s = i / 9.0;
    path.emplace_back(6.0 * s, 1.5 * std::sin(M_PI * s), 0.0);
  }
  DynamicLimits limits;
  limits.max_speed_mps = 2.0;
  limits.max_acceleration_mps2.setConstant(2.0);
  limits.max_jerk_mps3.setConstant(DynamicLimits::JerkBound(5.0, 2.0));
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        PlanMinTimeBSpline(path, Eigen::Vector3d(1.0, 0, 0), zero, zero, zero, limits));
  }
}
BENCHMARK(BM_MinTimeBSpline10Points)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace aperture::planning
