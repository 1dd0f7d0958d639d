// Cost of the sensor model alone (CameraEffects::ToImage8U: read + shot noise, gain, 8-bit
// quantization) on a 752 x 480 radiance image, the gap camera's size, gray and BGR. The CPU
// column is the whole process's CPU time per frame (all threads); range(1) = thread limit.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <opencv2/core.hpp>

#include "sim/render/camera_effects.h"

namespace aperture::sim {
namespace {

void BM_ToImage8U(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<size_t>(state.range(1)));
  const int channels = static_cast<int>(state.range(0));
  // A gradient over the sensor range, so shot noise varies over the image like a real scene.
  cv::Mat radiance(480, 752, channels == 1 ? CV_32FC1 : CV_32FC3);
  cv::randu(radiance, 0.0, 1.2);
  CameraEffectsParams params;  // the gap camera's noise (sim/scenario/builtin_scenarios.cc)
  params.read_noise_sigma = 0.004;
  params.full_well_electrons = 5000.0;
  const CameraEffects effects(params);
  int index = 0;
  for (auto _ : state) {
    const cv::Mat image = effects.ToImage8U(radiance, index++);
    benchmark::DoNotOptimize(image.data);
  }
}

// Args: {channels, threads}.
BENCHMARK(BM_ToImage8U)
    ->ArgNames({"channels", "threads"})
    ->ArgsProduct({{1, 3}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace aperture::sim
