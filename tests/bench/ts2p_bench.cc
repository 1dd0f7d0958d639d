// TS²P detection (seed 002 Sec. II) and label propagation (Alg. 1) per frame at 576 x 384 on one
// core (cv::setNumThreads(1)). Targets (issue 13): detection with N = 4 <= 100 ms, label
// propagation <= 1 ms per frame (paper: KLT 2 ms). Synthetic stack: a textured wall with an
// elliptic hole moving 6 px per step over a background moving 2 px per step (Z_B / Z_F = 3).
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/ts2p/label_tracker.h"
#include "perception/ts2p/ts2p_detector.h"

namespace aperture::perception {
namespace {

cv::Mat Texture(cv::Size size, int seed) {
  cv::RNG rng(seed);
  cv::Mat noise(size, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

cv::Mat Shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, dx, 0, 1, dy), image.size(), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  return out;
}

// Frame at scan offset k: background shifted 2 k px, wall (with its hole) 6 k px, along x.
cv::Mat StackFrame(int k) {
  static const cv::Mat wall = Texture({576, 384}, 1), background = Texture({576, 384}, 2);
  cv::Mat hole = cv::Mat::zeros(wall.size(), CV_8U);
  cv::ellipse(hole, cv::Point(288, 192), cv::Size(110, 80), 0, 0, 360, 255, -1);
  cv::Mat frame = Shifted(wall, 6.0 * k, 0.0);
  Shifted(background, 2.0 * k, 0.0).copyTo(frame, Shifted(hole, 6.0 * k, 0.0));
  return frame;
}

void BM_Ts2pDetection(benchmark::State& state) {
  cv::setNumThreads(1);
  Ts2pParams params;
  if (state.range(0) == 1) params.flow.method = "dis_fast";
  Ts2pDetector detector(params);
  const cv::Mat reference = StackFrame(0);
  const std::vector<cv::Mat> frames{StackFrame(-2), StackFrame(-1), StackFrame(1), StackFrame(2)};
  for (auto _ : state) benchmark::DoNotOptimize(detector.Detect(reference, frames));
  state.SetLabel(detector.FlowName() + ", N = 4, 576x384");
}
BENCHMARK(BM_Ts2pDetection)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Alg. 1 steps 2-6 for both sets (the fit and the composed propagation), and the whole
// per-frame track including KLT, on a 1 %/frame zoom.
void BM_LabelTracking(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat texture = Texture({576, 384}, 3);
  cv::Mat opening = cv::Mat::zeros(texture.size(), CV_8U);
  cv::ellipse(opening, cv::Point(288, 192), cv::Size(110, 80), 0, 0, 360, 255, -1);
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 16; ++k) {
    const double s = std::pow(1.01, k);
    cv::Mat zoomed;
    cv::warpAffine(texture, zoomed, cv::Matx23d(s, 0, (1 - s) * 300, 0, s, (1 - s) * 180),
                   texture.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    frames.push_back(zoomed);
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(opening.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  LabelTracker tracker(LabelTrackerParams{});
  double propagation_ms = 0.0, klt_ms = 0.0;
  int tracked = 0, k = 1;
  tracker.Initialize(frames[0], opening, {288, 192}, contours[0], 0.0, 0);
  for (auto _ : state) {
    if (k == static_cast<int>(frames.size())) {
      state.PauseTiming();
      tracker.Initialize(frames[0], opening, {288, 192}, contours[0], 0.0, 0);
      k = 1;
      state.ResumeTiming();
    }
    const OpeningTrack track = tracker.Track(frames[k], k / 30.0, k);
    propagation_ms += track.propagation_ms;
    klt_ms += track.klt_ms;
    ++tracked;
    ++k;
  }
  state.counters["propagation_ms"] = propagation_ms / tracked;
  state.counters["klt_ms"] = klt_ms / tracked;
}
BENCHMARK(BM_LabelTracking)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace aperture::perception
