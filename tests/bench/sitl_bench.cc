// Real-time factor of the lockstep SITL runner: 2 s of ground-truth hover (1 kHz dynamics and
// flight controller, 500 Hz IMU, 100 Hz autopilot, collision checks) with one 30 Hz 752 x 480
// pinhole camera (gray, noise on, ground truth off) looking at a textured wall and ground, and
// without camera. Reports "real_time_factor" (simulated over wall time) and the wall-time share
// of rendering. Thread limit range(1) (0: oneTBB default) as in render_bench.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/scene/textures.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::sim {
namespace {

Scene WallScene() {
  Scene scene;
  ProceduralTextureParams texture;
  scene.AddObject({"ground", GroundPlane{}, Material{MakeGrassTexture(texture)}});
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(4.0, 0.0, 1.5);
  scene.AddObject(
      {"wall", Box{Eigen::Vector3d(0.2, 8.0, 3.0)}, Material{MakeNewspaperTexture(texture)}, T_WO});
  return scene;
}

void Hover(benchmark::State& state) {
  std::unique_ptr<tbb::global_control> limit;
  if (state.range(1) > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(state.range(1)));
  }
  const Scene scene = WallScene();
  SitlRunnerParams params;
  params.duration_s = 2.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  if (state.range(0) != 0) {
    SitlCamera camera;
    camera.model = std::make_shared<perception::PinholeCamera>(
        752, 480, perception::PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
    camera.T_BC.linear() = perception::OpticalAxesAlongX();  // looking along x_B
    camera.rate_hz = 30.0;
    camera.effects.full_well_electrons = 5000.0;
    camera.effects.read_noise_sigma = 0.005;
    camera.render.ground_truth = false;
    params.cameras.push_back(camera);
  }
  SitlRunner runner(params, &scene);
  GroundTruthAutopilotParams autopilot_params;
  autopilot_params.waypoints.push_back(Waypoint{params.initial_state.p_WB, 0.0, 0.0});
  double sim_s = 0.0, wall_s = 0.0, render_s = 0.0;
  for (auto _ : state) {
    GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
    const SitlResult result = runner.Run(autopilot);
    sim_s += result.sim_time_s;
    wall_s += result.timing.wall_time_s;
    render_s += result.timing.render_s;
  }
  state.counters["real_time_factor"] = sim_s / wall_s;
  state.counters["render_share"] = render_s / wall_s;
}
BENCHMARK(Hover)
    ->ArgNames({"camera", "threads"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace aperture::sim
