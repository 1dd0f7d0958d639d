// Per-frame cost of monocular depth (seed 003 Sec. III-A) on a 640x480 colour frame, the forest
// camera's size: the 102 patch energies alone, and the whole estimate (energies + the shipped
// linear SVM over the 40 x 30 patch grid). Target: <= 50 ms per frame on one core (issue 17).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/mono_depth/mono_depth_estimator.h"

namespace aperture::perception {
namespace {

cv::Mat MakeColourFrame() {
  cv::Mat bgr(480, 640, CV_8UC3);
  cv::randu(bgr, cv::Scalar::all(0), cv::Scalar::all(256));
  cv::GaussianBlur(bgr, bgr, cv::Size(), 1.5);
  return bgr;
}

void BM_MonoDepthFeatures640x480(benchmark::State& state) {
  const cv::Mat bgr = MakeColourFrame();
  MonoDepthFeatureExtractor extractor;
  for (auto _ : state) benchmark::DoNotOptimize(extractor.Extract(bgr));
}
BENCHMARK(BM_MonoDepthFeatures640x480)->Unit(benchmark::kMillisecond);

void BM_MonoDepthEstimate640x480(benchmark::State& state) {
  const cv::Mat bgr = MakeColourFrame();
  MonoDepthEstimator estimator(DefaultMonoDepthModel());
  for (auto _ : state) benchmark::DoNotOptimize(estimator.Estimate(bgr));
}
BENCHMARK(BM_MonoDepthEstimate640x480)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace aperture::perception
