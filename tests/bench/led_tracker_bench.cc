// LED front-end costs per 752x480 frame (Faessler thesis Table C.2 reports the same steps).
// Targets (report only): detection with ROIs <= 1 ms, brute-force correspondences with 5 LEDs +
// 1 false detection <= 1 ms, prediction + verification + refinement <= 0.1 ms.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <vector>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/led/led_configuration.h"
#include "perception/led/led_correspondence_search.h"
#include "perception/led/led_detector.h"
#include "perception/led/led_pose_refiner.h"
#include "perception/led/led_tracker.h"

namespace aperture::perception {
namespace {

struct Fixture {
  std::shared_ptr<const CameraModel> camera =
      std::make_shared<PinholeCamera>(752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
  LedConfiguration configuration = LedConfiguration::Default();
  Eigen::Isometry3d T_CT = Eigen::Translation3d(0.05, -0.03, 1.4) *
                          Eigen::AngleAxisd(2.9, Eigen::Vector3d(1.0, 0.07, 0.1).normalized());
  std::vector<Eigen::Vector2d> px;  // true projections
  cv::Mat image;                     // Gaussian LED blobs (sigma 1.5 px) + a dim noisy background

  Fixture() {
    cv::Mat radiance(480, 752, CV_32FC1);
    cv::randn(radiance, 8.0, 2.0);  // dark infrared background
    for (const auto& p_T : configuration.p_T()) {
      px.emplace_back();
      if (!camera->Project(T_CT * p_T, &px.back()) || !camera->IsInImage(px.back(), 8.0)) {
        throw std::logic_error("benchmark target not in view");
      }
      for (int y = static_cast<int>(px.back().y()) - 6; y <= px.back().y() + 6; ++y) {
        for (int x = static_cast<int>(px.back().x()) - 6; x <= px.back().x() + 6; ++x) {
          const double d2 = (Eigen::Vector2d(x, y) - px.back()).squaredNorm();
          radiance.at<float>(y, x) += static_cast<float>(210.0 * std::exp(-d2 / 4.5));
        }
      }
    }
    radiance.convertTo(image, CV_8UC1);
  }

  std::vector<LedDetection> Detections(bool with_outlier) const {
    std::vector<LedDetection> detections;
    for (const auto& p : px) {
      detections.push_back({p, camera->Unproject(p), 1.0, 9});
    }
    if (with_outlier) {
      const Eigen::Vector2d false_px = px[0] + Eigen::Vector2d(12.0, -9.0);
      detections.push_back({false_px, camera->Unproject(false_px), 1.0, 9});
    }
    return detections;
  }
};

void BM_LedDetectionWithRois(benchmark::State& state) {
  const Fixture fixture;
  std::vector<cv::Rect> rois;
  for (const auto& p : fixture.px) {
    rois.emplace_back(static_cast<int>(p.x()) - 24, static_cast<int>(p.y()) - 24, 49, 49);
  }
  LedDetector detector;
  for (auto _ : state) {
    benchmark::DoNotOptimize(detector.Detect(fixture.image, *fixture.camera, rois));
  }
}
BENCHMARK(BM_LedDetectionWithRois)->Unit(benchmark::kMicrosecond);

void BM_LedDetectionFullImage(benchmark::State& state) {
  const Fixture fixture;
  LedDetector detector;
  for (auto _ : state) {
    benchmark::DoNotOptimize(detector.Detect(fixture.image, *fixture.camera));
  }
}
BENCHMARK(BM_LedDetectionFullImage)->Unit(benchmark::kMicrosecond);

// Argument: 0 = Kneip (own), 1 = Kneip through OpenGV, 2 = AP3P (OpenCV).
void BM_LedBruteForceFiveLedsOneOutlier(benchmark::State& state) {
  const Fixture fixture;
  LedCorrespondenceParams params;
  params.p3p_method = std::array<P3pMethod, 3>{P3pMethod::kKneip, P3pMethod::kOpenGv,
                                                P3pMethod::kAp3p}[state.range(0)];
  const LedCorrespondenceSearch search(fixture.configuration.p_T(), params);
  const std::vector<LedDetection> detections = fixture.Detections(true);
  int found = 0;
  for (auto _ : state) {
    const LedCorrespondenceResult result = search.FindByBruteForce(detections, *fixture.camera);
    found = static_cast<int>(result.correspondences.size());
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(P3pMethodName(params.p3p_method) + ", " + std::to_string(found) +
                 " correspondences");
}
BENCHMARK(BM_LedBruteForceFiveLedsOneOutlier)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMicrosecond);

// Tracking step without detection: prediction (C.6), nearest-detection matching, verification
// (C.3.5) and Gauss-Newton refinement with covariance (C.8), (C.9).
void BM_LedPredictVerifyRefine(benchmark::State& state) {
  const Fixture fixture;
  const std::vector<LedDetection> detections = fixture.Detections(false);
  LedTracker tracker(fixture.configuration, fixture.camera);
  tracker.Track(fixture.image, 0.0);
  tracker.Track(fixture.image, 0.02);
  const LedCorrespondenceSearch search(fixture.configuration.p_T());
  std::vector<LedCorrespondence> matches;
  std::vector<Eigen::Vector3d> p_T;
  std::vector<Eigen::Vector2d> px;
  for (auto _ : state) {
    const Eigen::Isometry3d predicted = *tracker.Predict(0.04);
    matches.clear();
    p_T.clear();
    px.clear();
    for (int led = 0; led < fixture.configuration.size(); ++led) {
      Eigen::Vector2d projected;
      fixture.camera->Project(predicted * fixture.configuration.p_T()[led], &projected);
      for (int d = 0; d < static_cast<int>(detections.size()); ++d) {
        if ((detections[d].px - projected).squaredNorm() < 25.0) {
          matches.push_back({led, d});
          p_T.push_back(fixture.configuration.p_T()[led]);
          px.push_back(detections[d].px);
          break;
        }
      }
    }
    benchmark::DoNotOptimize(search.Verify(matches, detections, *fixture.camera));
    benchmark::DoNotOptimize(RefineLedPose(*fixture.camera, p_T, px, predicted));
  }
}
BENCHMARK(BM_LedPredictVerifyRefine)->Unit(benchmark::kMicrosecond);

// Refinement alone (the thesis' "pose optimization" step).
void BM_LedRefine(benchmark::State& state) {
  const Fixture fixture;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        RefineLedPose(*fixture.camera, fixture.configuration.p_T(), fixture.px, fixture.T_CT));
  }
}
BENCHMARK(BM_LedRefine)->Unit(benchmark::kMicrosecond);

// A whole tracked frame: ROI detection + prediction + verification + refinement.
void BM_LedTrackFrame(benchmark::State& state) {
  const Fixture fixture;
  LedTracker tracker(fixture.configuration, fixture.camera);
  double t_s = 0.0;
  tracker.Track(fixture.image, t_s);
  int tracked = 0, frames = 0;
  for (auto _ : state) {
    t_s += 0.02;
    const LedTrackResult result = tracker.Track(fixture.image, t_s);
    tracked += result.status == LedTrackStatus::kTracked ? 1 : 0;
    ++frames;
  }
  state.SetLabel(std::to_string(tracked) + "/" + std::to_string(frames) + " tracked");
}
BENCHMARK(BM_LedTrackFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::perception
