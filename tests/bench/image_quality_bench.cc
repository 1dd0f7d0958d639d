// Per-frame cost of the image_quality front end on a 752x480 (WVGA global-shutter) image.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/quality/image_quality_analyzer.h"

namespace aperture::perception {
namespace {

cv::Mat MakeImage(int type) {
  cv::Mat gray(480, 752, CV_8UC1);
  cv::randu(gray, 0, 256);
  cv::GaussianBlur(gray, gray, cv::Size(), 2.0);
  if (type == CV_8UC1) return gray;
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

void BM_ImageQualityGray752x480(benchmark::State& state) {
  const cv::Mat image = MakeImage(CV_8UC1);
  ImageQualityAnalyzer analyzer;
  for (auto _ : state) benchmark::DoNotOptimize(analyzer.Analyze(image));
}
BENCHMARK(BM_ImageQualityGray752x480)->Unit(benchmark::kMicrosecond);

void BM_ImageQualityBgr752x480(benchmark::State& state) {
  const cv::Mat image = MakeImage(CV_8UC3);
  ImageQualityAnalyzer analyzer;
  for (auto _ : state) benchmark::DoNotOptimize(analyzer.Analyze(image));
}
BENCHMARK(BM_ImageQualityBgr752x480)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::perception
