// AprilTag front-end cost per 640x480 frame with 12 tags in view (issue 15: detection + pose
// <= 4 ms on one core; the apriltag library alone floors at ~2.8 ms at decimate 2). The frame is
// ray-traced once: 12 tag36h11 tags of 0.3 m on the ground in a 4 x 3 grid, some tilted, seen from
// 2.6 m by a 90 deg pinhole camera with sensor noise. Every detector runs single-threaded; every
// benchmark runs a fixed number of frames 5 times and reports mean, median and spread only:
//   Detect/<detector>/<decimate x10>/<min_white_black_diff>
//                                       detection only; for the apriltag library its own stage
//                                       profile as counters (us per frame, wall)
//   FrontEnd/<detector>/<decimate x10>  TagFrontEnd::Process, what the `apriltag` node runs per
//                                       frame: detection, pose (corner undistortion, IPPE, both
//                                       candidates refined by Gauss-Newton with covariance) and
//                                       flip resolution
//   PoseStage/<stage>                   the pose of the 12 detections (per tag: time / 12) by
//                                       stage: 0 corner undistortion (CameraModel::Unproject),
//                                       1 IPPE (IppeSquare), 2 EstimateTagPose (all), and for
//                                       comparison 3 OpenCV's IPPE (solvePnPGeneric with
//                                       SOLVEPNP_IPPE_SQUARE, what the front end used before)
// Run on an idle core (`uptime`; optionally `taskset -c 1`) and report the load.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/camera/pinhole_camera.h"
#include "perception/tags/apriltag_library_detector.h"
#include "perception/tags/ippe_square.h"
#include "perception/tags/tag_front_end.h"
#include "perception/tags/tag_pose_estimator.h"
#include "servo/visp_tag_detector.h"
#include "sim/render/camera_effects.h"
#include "sim/scene/apriltag_object.h"
#include "sim/scene/scene.h"

namespace aperture {
namespace {

constexpr double kTagSize_m = 0.3;

struct Frame12 {
  std::shared_ptr<const perception::CameraModel> camera =
      std::make_shared<perception::PinholeCamera>(
          640, 480, perception::PinholeIntrinsics{320.0, 320.0, 319.5, 239.5});
  cv::Mat image;

  Frame12() {
    sim::Scene scene;
    scene.AddObject({"ground", sim::GroundPlane{}, {}, Eigen::Isometry3d::Identity()});
    for (int id = 0; id < 12; ++id) {
      Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
      // 0.1 m above the ground: a tilted tag's lower edge stays above it (not occluded).
      T_WO.translation() = Eigen::Vector3d(1.0 * (id % 4) - 1.5, 1.0 * (id / 4) - 1.0, 0.1);
      // z_O down into the ground, yaw by id, every third tag tilted 30 deg.
      T_WO.linear() =
          (Eigen::AngleAxisd(0.4 * id, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(M_PI + (id % 3 == 0 ? 0.5 : 0.0), Eigen::Vector3d::UnitX()))
              .toRotationMatrix();
      scene.AddObject(sim::MakeAprilTagObject("tag36h11", id, kTagSize_m, T_WO));
    }
    Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
    T_WC.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    T_WC.translation() = Eigen::Vector3d(0.0, 0.0, 2.6);
    sim::CameraEffectsParams effects;
    effects.read_noise_sigma = 0.004;
    effects.full_well_electrons = 5000;
    sim::RayCaster caster;
    sim::RenderOptions render;
    render.supersampling = 2;
    image = sim::CameraEffects(effects)
                .Capture(
                    caster, scene, *camera, [&](double) { return T_WC; }, 0.0, 0, render)
                .frame.image;
  }
};

const Frame12& Fixture() {
  static const Frame12 frame;
  return frame;
}

constexpr int kFrames = 50;  // per repetition (0.1-2 s)
constexpr int kPoseIterations = 2000;
constexpr int kRepetitions = 5;

std::unique_ptr<perception::TagDetector> MakeDetector(bool visp, double decimate,
                                                      int min_white_black_diff) {
  perception::TagDetectorParams params;
  params.quad_decimate = decimate;
  params.min_white_black_diff = min_white_black_diff;
  params.threads = 1;
  if (visp) return servo::CreateVispTagDetector(params);
  return std::make_unique<perception::AprilTagLibraryDetector>(params);
}

void CheckTwelve(benchmark::State& state, std::size_t found) {
  state.counters["tags"] = static_cast<double>(found);
  if (found != 12) state.SkipWithError("expected 12 tags in the benchmark frame");
}

void BM_Detect(benchmark::State& state, bool visp) {
  const Frame12& frame = Fixture();
  const std::unique_ptr<perception::TagDetector> detector =
      MakeDetector(visp, state.range(0) / 10.0, static_cast<int>(state.range(1)));
  auto* library = dynamic_cast<perception::AprilTagLibraryDetector*>(detector.get());
  std::map<std::string, double> stage_s;
  std::size_t found = 0;
  for (auto _ : state) {
    found = detector->Detect(frame.image).size();
    if (!library) continue;
    for (const auto& [stage, seconds] : library->LastStageTimes()) stage_s[stage] += seconds;
  }
  for (const auto& [stage, seconds] : stage_s) {
    state.counters[stage + "_us"] = 1e6 * seconds / static_cast<double>(state.iterations());
  }
  CheckTwelve(state, found);
}

void BM_FrontEnd(benchmark::State& state, bool visp) {
  const Frame12& frame = Fixture();
  perception::TagFrontEndParams params;
  params.detection.quad_decimate = state.range(0) / 10.0;
  params.size_m = kTagSize_m;
  perception::TagFrontEnd front_end(
      MakeDetector(visp, params.detection.quad_decimate, params.detection.min_white_black_diff),
      frame.camera, params);
  std::size_t posed = 0;
  double t_s = 0.0;
  for (auto _ : state) {
    const perception::TagFrameResult result = front_end.Process(frame.image, t_s);
    t_s += 0.05;
    posed = std::count_if(result.tags.begin(), result.tags.end(),
                          [](const perception::TagResult& tag) { return tag.pose.has_value(); });
  }
  CheckTwelve(state, posed);
}

void Configure(benchmark::internal::Benchmark* benchmark) {
  benchmark->Unit(benchmark::kMillisecond)
      ->Iterations(kFrames)
      ->Repetitions(kRepetitions)
      ->ReportAggregatesOnly(true);
}
// Detect: <decimate x10>/<min_white_black_diff>: the library's default contrast (5) against ours
// (20); ViSP cannot set it (keeps 5).
BENCHMARK_CAPTURE(BM_Detect, apriltag, false)->ArgsProduct({{10, 20}, {5, 20}})->Apply(Configure);
BENCHMARK_CAPTURE(BM_Detect, visp, true)->ArgsProduct({{10, 20}, {5}})->Apply(Configure);
// FrontEnd: <decimate x10>, every other setting the front end's default.
BENCHMARK_CAPTURE(BM_FrontEnd, apriltag, false)->Arg(10)->Arg(20)->Apply(Configure);
BENCHMARK_CAPTURE(BM_FrontEnd, visp, true)->Arg(10)->Arg(20)->Apply(Configure);

enum PoseStage { kUndistort = 0, kIppe = 1, kEstimateTagPose = 2, kOpenCvIppe = 3 };

void BM_PoseStage(benchmark::State& state) {
  const Frame12& frame = Fixture();
  const std::vector<perception::TagDetection> detections =
      MakeDetector(false, 1.0, perception::TagDetectorParams{}.min_white_black_diff)
          ->Detect(frame.image);
  std::vector<cv::Point3d> object;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d p_T = perception::TagCorner(k, kTagSize_m);
    object.emplace_back(p_T.x(), p_T.y(), 0.0);
  }
  std::vector<std::array<Eigen::Vector2d, 4>> normalized;
  std::vector<std::vector<cv::Point2d>> normalized_cv;
  for (const perception::TagDetection& detection : detections) {
    normalized.emplace_back();
    normalized_cv.emplace_back();
    for (int k = 0; k < 4; ++k) {
      normalized.back()[k] = frame.camera->Unproject(detection.corners_px[k]).hnormalized();
      normalized_cv.back().emplace_back(normalized.back()[k].x(), normalized.back()[k].y());
    }
  }
  const auto stage = static_cast<PoseStage>(state.range(0));
  for (auto _ : state) {
    for (std::size_t i = 0; i < detections.size(); ++i) {
      if (stage == kUndistort) {
        for (const Eigen::Vector2d& corner_px : detections[i].corners_px) {
          benchmark::DoNotOptimize(frame.camera->Unproject(corner_px));
        }
      } else if (stage == kIppe) {
        benchmark::DoNotOptimize(perception::IppeSquare(normalized[i], kTagSize_m));
      } else if (stage == kEstimateTagPose) {
        benchmark::DoNotOptimize(
            perception::EstimateTagPose(*frame.camera, detections[i].corners_px, kTagSize_m));
      } else {
        std::vector<cv::Mat> rvecs, tvecs;
        benchmark::DoNotOptimize(cv::solvePnPGeneric(object, normalized_cv[i], cv::Matx33d::eye(),
                                                     cv::noArray(), rvecs, tvecs, false,
                                                     cv::SOLVEPNP_IPPE_SQUARE));
      }
    }
  }
  CheckTwelve(state, detections.size());
}
BENCHMARK(BM_PoseStage)
    ->DenseRange(kUndistort, kOpenCvIppe)
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(kPoseIterations)
    ->Repetitions(kRepetitions)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace aperture
