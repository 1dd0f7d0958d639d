// GapDetector per 752 x 480 frame (seed 000 reports > 30 Hz onboard): full-image search and ROI
// tracking around the previous detection, on a rendered gap 3 m away, pinhole and 180 deg
// fisheye. Targets (one core): full search <= 2 ms, ROI tracking <= 0.5 ms.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/camera/equidistant_camera.h"
#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/gap/canny_edge_detector.h"
#include "perception/gap/gap_detector.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/gap_pattern_object.h"

namespace aperture::sim {
namespace {

std::shared_ptr<const perception::CameraModel> Camera(bool fisheye) {
  if (fisheye) {
    return std::make_shared<perception::EquidistantCamera>(
        752, 480, perception::PinholeIntrinsics{215.0, 215.0, 375.5, 239.5},
        perception::EquidistantDistortion{-0.02, 0.003, 0.0, 0.0});
  }
  return std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
}

// A gap (roll 0.4 rad) 3 m in front of the camera, a noise-textured wall behind, grass below.
cv::Mat RenderGapFrame(const perception::CameraModel& camera) {
  Scene scene;
  ProceduralTextureParams tex;
  scene.AddObject(
      {"ground", GroundPlane{}, {MakeGrassTexture(tex)}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  T_WG.linear() = perception::OpticalAxesAlongX() *
                  Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WG.translation() = Eigen::Vector3d(3.0, 0.2, 1.6);
  scene.AddObject(
      MakeGapPatternObject(perception::GapDetectorParams{}, Eigen::Vector2d(1.8, 1.2), T_WG));
  Eigen::Isometry3d T_WBack = T_WG;
  T_WBack.translation() = Eigen::Vector3d(8.0, 0.0, 2.0);
  scene.AddObject(
      {"background", Rectangle{{20.0, 5.0}, {}, {}}, {MakeValueNoiseTexture(tex)}, T_WBack});
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() = perception::OpticalAxesAlongX();  // looking along +x_W, image down = -z_W
  T_WC.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;
  return CameraEffects({}).ToImage8U(caster.Render(scene, camera, T_WC, options).radiance, 0);
}

void BM_GapDetector(benchmark::State& state) {
  tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
  const bool fisheye = state.range(0) != 0;
  const bool roi = state.range(1) != 0;
  const auto camera = Camera(fisheye);
  const cv::Mat image = RenderGapFrame(*camera);
  perception::GapDetector detector(perception::GapDetectorParams{}, camera);
  if (!detector.Detect(image).detected()) {
    state.SkipWithError("gap not detected in the benchmark frame");
    return;
  }
  int found = 0;
  for (auto _ : state) {
    const perception::GapDetection d =
        roi ? detector.Detect(image) : detector.DetectFullImage(image);
    found += d.detected() && d.from_roi == roi ? 1 : 0;
    benchmark::DoNotOptimize(d.T_CG);
  }
  state.counters["found_ratio"] = static_cast<double>(found) / state.iterations();
  state.SetLabel(std::string(fisheye ? "fisheye" : "pinhole") + (roi ? " roi" : " full"));
}
BENCHMARK(BM_GapDetector)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

// The detector's first stage on the same full frames: OpenCV's Canny + 3x3 dilation (what the
// detector ran before) against CannyEdgeDetector, which gives the identical edge image.
void BM_GapEdgeStage(benchmark::State& state) {
  tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
  cv::setNumThreads(1);
  const bool fisheye = state.range(0) != 0;
  const bool opencv = state.range(1) != 0;
  const auto camera = Camera(fisheye);
  const cv::Mat gray = RenderGapFrame(*camera);  // CV_8UC1 (gray scene)
  cv::Mat edges;
  const perception::GapDetectorParams params;
  perception::CannyEdgeDetector canny;
  for (auto _ : state) {
    if (opencv) {
      cv::Canny(gray, edges, params.canny_low, params.canny_high);
      cv::dilate(edges, edges, cv::Mat());
    } else {
      canny.Detect(gray, cv::Rect(0, 0, gray.cols, gray.rows), params.canny_low, params.canny_high,
                   true, &edges);
    }
    benchmark::DoNotOptimize(edges.data);
  }
  state.SetLabel(std::string(fisheye ? "fisheye" : "pinhole") +
                 (opencv ? " cv::Canny+dilate" : " CannyEdgeDetector"));
}
BENCHMARK(BM_GapEdgeStage)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::sim
