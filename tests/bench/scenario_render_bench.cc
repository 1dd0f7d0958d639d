// Frame rate of `aperture render` per built-in scenario: one captured frame (render + sensor
// effects) of the scenario's render camera at its start pose, at the scenario's own settings
// (gap: 752 x 480 fisheye with 2 x 2 supersampling). Reports frames/s ("fps").
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
  Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig(name)));
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RayCaster caster;
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
    ->UseRealTime();

}  // namespace
}  // namespace aperture::sim
