#pragma once
// One rendered TS²P detection scan of `aperture bench ts2p` (seed 002, Sec. IV-A: "the quadrotor
// executes a fixed diagonal straight line trajectory ... while taking a number of images along
// its path"): the simulator's `gapflyt` scene (textured foreground wall with an opening of one of
// the five shapes, textured background wall), the camera at the reference pose looking along +x_W
// and the N stack frames at offsets (k - N/2) * scan_step_m along a straight line in the wall's
// plane (k = 0..N, the reference k = N/2 left out), so the reference sits mid-scan.
// Truth G: the reference pixels whose object id is not the foreground wall's and whose depth is
// behind the wall's plane (the opening as the renderer's id mask and depth show it; the ground in
// front of the wall at the image bottom is not part of it).
//
//   Ts2pScanConfig config = DrawTs2pTrial(Ts2pTrialRanges{}, /*seed=*/1, /*trial=*/7);
//   Ts2pScan scan = RenderTs2pScan(config, caster);
//   Ts2pDetection d = detector.Detect(scan.reference, scan.frames);
//   OpeningScore s = ScoreOpening(d.opening, scan.truth);
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"
#include "sim/render/ray_caster.h"

namespace aperture::experiments {

struct Ts2pScanConfig {
  std::string shape = "polygon";  // GapFlytParams::shape
  std::uint64_t seed = 0;         // textures and the polygon's corners
  int width = 576;                // seed 002 Fig. 12: 576 x 384
  int height = 384;
  double fov_deg = 80.0;
  double foreground_depth_m = 2.6;  // 0Z_F, camera to the foreground wall (paper ~2.6 m)
  double background_depth_m = 5.7;  // 0Z_B (paper ~5.7 m)
  Eigen::Vector2d opening_size_m = Eigen::Vector2d(1.0, 0.8);
  // Opening centre relative to the camera's optical axis, (right, up) in the wall [m].
  Eigen::Vector2d opening_offset_m = Eigen::Vector2d::Zero();
  int stack = 4;                 // N
  double scan_step_m = 0.05;     // baseline between consecutive scan positions [m]
  double scan_angle_deg = 45.0;  // scan direction in the wall plane from "right" towards "up"
  // Camera rotation per scan step, [roll about z_C, pitch about x_C, yaw about y_C] [deg]
  // (0 = the paper's rotation-free scan; non-zero exercises gyro derotation).
  Eigen::Vector3d rotation_per_step_deg = Eigen::Vector3d::Zero();
};

struct Ts2pScan {
  cv::Mat reference;                    // CV_8UC1
  std::vector<cv::Mat> frames;          // N, CV_8UC1
  std::vector<Eigen::Matrix3d> R_CkCr;  // true camera rotations (what a gyro integrates)
  cv::Mat truth;                        // CV_8UC1, 255 = G in the reference
  std::shared_ptr<const perception::CameraModel> camera;
};

// std::invalid_argument for a stack < 1 or a scene that cannot be built (names the field).
Ts2pScan RenderTs2pScan(const Ts2pScanConfig& config, sim::RayCaster& caster);

// The approach after the detection (Table III analog): `frames` images from the scan's reference
// pose straight towards the wall (+x_W) at speed_mps, 30 Hz, first frame one step ahead of the
// reference; truth[k] = G of frame k.
struct Ts2pApproach {
  std::vector<cv::Mat> frames;  // CV_8UC1
  std::vector<cv::Mat> truth;   // CV_8UC1, 255 = G
  double frame_rate_hz = 30.0;
};
Ts2pApproach RenderTs2pApproach(const Ts2pScanConfig& config, int frames, double speed_mps,
                                sim::RayCaster& caster);

// What `aperture bench ts2p` randomizes per trial (uniform in [min, max]).
struct Ts2pTrialRanges {
  Eigen::Vector2d foreground_depth_m = Eigen::Vector2d(2.2, 3.0);  // around the paper's 2.6 m
  Eigen::Vector2d background_depth_m = Eigen::Vector2d(5.0, 6.5);  // around 5.7 m
  Eigen::Vector2d width_m = Eigen::Vector2d(0.8, 1.2);             // opening bounding box
  Eigen::Vector2d height_m = Eigen::Vector2d(0.6, 1.0);
  double max_offset_m = 0.2;  // opening centre off the optical axis, per axis
  Eigen::Vector2d scan_angle_deg = Eigen::Vector2d(0.0, 180.0);
};

extern const std::vector<std::string> kTs2pShapes;  // the five GapFlytParams shapes

// Trial `trial` of a bench seeded `seed`: shape = kTs2pShapes[trial % 5], the rest drawn from
// `ranges` by a generator of (seed, trial) only.
Ts2pScanConfig DrawTs2pTrial(const Ts2pTrialRanges& ranges, std::uint64_t seed, int trial);

}  // namespace aperture::experiments
