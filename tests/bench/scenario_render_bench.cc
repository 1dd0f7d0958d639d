// Frame rate of `aperture render` per built-in scenario: one captured frame (render + sensor
// effects) of the scenario's render camera at its start pose, at the scenario's own settings
// (gap: 752 x 480 fisheye with 2 x 2 supersampling). Reports frames/s ("fps"); the CPU column is
// the whole process's CPU time per frame (all threads), which stays comparable when the machine
// is shared. BM_RenderGapFrame: the ray caster alone on the gap scenario's 752 x 480 180 deg
// fisheye (ground truth on), the frame-rate target (>= 60 frames/s on 2 cores).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>

#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

const char* const kScenarios[] = {"gap", "gapflyt", "led", "tags", "forest"};

void BM_CaptureScenarioFrame(benchmark::State& state) {
  const std::string name = kScenarios[state.range(0)];
  state.SetLabel(name);
  // range(1) = thread limit (0: oneTBB default); 1 thread gives the per-frame CPU cost.
  std::unique_ptr<tbb::global_control> limit;
  if (state.range(1) > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(state.range(1)));
  }
  const Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig(name)));
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RayCaster caster;
  caster.Render(scenario.scene(), *camera.model, T_WC, camera.render);  // builds the ray cache
  int index = 0;
  for (auto _ : state) {
    const CapturedFrame frame = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double) { return T_WC; }, 0.0, index++,
        camera.render);
    benchmark::DoNotOptimize(frame.frame.image.data);
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: {scenario index into kScenarios, thread limit}.
BENCHMARK(BM_CaptureScenarioFrame)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_RenderGapFrame(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<size_t>(state.range(1)));
  const Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig("gap")));
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RenderOptions options = camera.render;
  options.supersampling = static_cast<int>(state.range(0));
  RayCaster caster;
  RenderOutput output;
  caster.Render(scenario.scene(), *camera.model, T_WC, options, &output);  // builds the ray cache
  for (auto _ : state) {
    caster.Render(scenario.scene(), *camera.model, T_WC, options, &output);
    benchmark::DoNotOptimize(output.radiance.data);
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: {supersampling k, threads}.
BENCHMARK(BM_RenderGapFrame)
    ->ArgNames({"k", "threads"})
    ->ArgsProduct({{1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace aperture::sim
