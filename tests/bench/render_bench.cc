// Ray-caster throughput on a gap-like scene: a newspaper-textured wall with a rectangular hole
// 3 m in front of the camera, a value-noise backdrop 3 m behind it and a grass ground plane.
// Reports frames/s ("fps") for 752 x 480 fisheye and pinhole frames (gray, ground truth on).
// BM_RenderScenarioBackend: the two ray-object back ends side by side (ray_caster.h RayBackend:
// our tile culling vs Intel Embree 3) on the gap, gapflyt, tags and forest scenarios' render
// camera at its start pose and the scenario's own render settings (docs/results/speed.md).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>

#include "perception/camera/equidistant_camera.h"
#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/render/embree_scene.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

Eigen::Isometry3d Pose(double rx, double ry, double rz, const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = p;
  return T;
}

Scene GapScene() {
  Scene scene;
  ProceduralTextureParams params;
  scene.AddObject(
      {"ground", GroundPlane{}, {MakeGrassTexture(params)}, Eigen::Isometry3d::Identity()});
  // Walls stand in planes x_W = const: z_O along +x_W, x_O along -y_W, y_O down (-z_W).
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  T_WG.linear() = perception::OpticalAxesAlongX();
  T_WG.translation() = Eigen::Vector3d(3.0, 0.0, 1.5);
  Rectangle wall{{4.0, 3.0}, {{{-0.4, -0.3}, {0.4, -0.3}, {0.4, 0.3}, {-0.4, 0.3}}}, {}};
  scene.AddObject({"gap", wall, {MakeNewspaperTexture(params)}, T_WG});
  Eigen::Isometry3d T_WBack = T_WG;
  T_WBack.translation() = Eigen::Vector3d(6.0, 0.0, 2.0);
  scene.AddObject(
      {"background", Rectangle{{12.0, 4.0}, {}, {}}, {MakeValueNoiseTexture(params)}, T_WBack});
  return scene;
}

void RenderFrames(benchmark::State& state, const perception::CameraModel& camera) {
  const Scene scene = GapScene();
  // Camera 1.4 m above ground looking along +x_W at the gap, slightly yawed.
  const Eigen::Isometry3d T_WC =
      Pose(-M_PI / 2, 0.0, -M_PI / 2 + 0.05, Eigen::Vector3d(0.0, 0.1, 1.4));
  RenderOptions options;
  options.supersampling = static_cast<int>(state.range(0));
  // range(1) = thread limit (0: oneTBB default). One thread gives the per-frame CPU cost, which
  // stays meaningful when the machine is shared.
  std::unique_ptr<tbb::global_control> limit;
  if (state.range(1) > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(state.range(1)));
  }
  RayCaster caster;
  RenderOutput output;
  caster.Render(scene, camera, T_WC, options, &output);  // builds the ray cache
  for (auto _ : state) {
    caster.Render(scene, camera, T_WC, options, &output);
    benchmark::DoNotOptimize(output.radiance.data);
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RenderFisheye752x480(benchmark::State& state) {
  const perception::EquidistantCamera camera(752, 480, {215.0, 215.0, 375.5, 239.5},
                                             {-0.02, 0.003, 0.0, 0.0});
  RenderFrames(state, camera);
}

void BM_RenderPinhole752x480(benchmark::State& state) {
  const perception::PinholeCamera camera(752, 480, {420.0, 420.0, 375.5, 239.5});
  RenderFrames(state, camera);
}

// Args: {supersampling k, thread limit}.
BENCHMARK(BM_RenderFisheye752x480)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_RenderPinhole752x480)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

const char* const kBackendScenarios[] = {"gap", "gapflyt", "tags", "forest"};

void BM_RenderScenarioBackend(benchmark::State& state) {
  const std::string name = kBackendScenarios[state.range(0)];
  const auto backend = state.range(1) == 0 ? RayBackend::kTileCulling : RayBackend::kEmbree;
  if (backend == RayBackend::kEmbree && !EmbreeAvailable()) {
    state.SkipWithError("built without Embree (APERTURE_EMBREE=OFF)");
    return;
  }
  state.SetLabel(name + (backend == RayBackend::kEmbree ? "/embree" : "/ours"));
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<size_t>(state.range(2)));
  const Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig(name)));
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RayCaster caster(backend);
  RenderOutput output;
  caster.Render(scenario.scene(), *camera.model, T_WC, camera.render, &output);  // ray cache
  for (auto _ : state) {
    caster.Render(scenario.scene(), *camera.model, T_WC, camera.render, &output);
    benchmark::DoNotOptimize(output.radiance.data);
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: {scenario index into kBackendScenarios, backend (0 ours, 1 Embree), threads}.
BENCHMARK(BM_RenderScenarioBackend)
    ->ArgNames({"scene", "embree", "threads"})
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace aperture::sim
