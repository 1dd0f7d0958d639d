// TS²P on rendered scans of the gapflyt scene against the renderer's id masks (seed 002 Sec. IV),
// and gyro derotation on a rendered pure-rotation pair.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "experiments/ts2p/ts2p_scan.h"
#include "perception/ts2p/opening_score.h"
#include "perception/ts2p/ts2p_detector.h"

namespace aperture::experiments {
namespace {

// The default detector on `scan`: a detection in seed 002's sense (lambda_D >= 0.75) with few
// wall pixels called opening (Table II's best AFP is 0.02; one trial may be worse than the mean,
// not by 2x). Returns the detection for further checks.
perception::Ts2pDetection DetectAndScore(const Ts2pScan& scan, const std::string& label) {
  perception::Ts2pDetector detector(perception::Ts2pParams{});
  const perception::Ts2pDetection d = detector.Detect(scan.reference, scan.frames);
  EXPECT_TRUE(d.valid) << label << ": " << d.status;
  if (!d.valid) return d;
  const perception::OpeningScore score = perception::ScoreOpening(d.opening, scan.truth);
  EXPECT_GE(score.overlap, 0.75) << label;
  EXPECT_LE(score.false_positive, 0.04) << label;
  return d;
}

class Ts2pShapeTest : public ::testing::TestWithParam<std::string> {};

// Every shape at the paper's depths (Z_F 2.6 m, Z_B 5.7 m), N = 4, default detector: a
// detection in the paper's sense with few wall pixels called opening.
TEST_P(Ts2pShapeTest, DetectsTheOpeningOfEveryShape) {
  Ts2pScanConfig config;
  config.shape = GetParam();
  config.seed = 11;
  sim::RayCaster caster;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  ASSERT_EQ(scan.frames.size(), 4u);
  const perception::Ts2pDetection d = DetectAndScore(scan, GetParam());
  ASSERT_TRUE(d.valid);
  // The safe point lies inside the true opening.
  const cv::Point x_s(static_cast<int>(std::lround(d.safe_point_px.x())),
                      static_cast<int>(std::lround(d.safe_point_px.y())));
  EXPECT_NE(scan.truth.at<uchar>(x_s), 0) << "x_s " << d.safe_point_px.transpose();
  // The F mode is the wall's stacked parallax f * mean|baseline| / Z_F (offsets +-1, +-2 scan
  // steps: mean 1.5 steps); B moves less (Z_B / Z_F = 2.2, but flow bleeding from the wall into a
  // small opening raises its mode, up to 1.5x the true value on the star).
  const double f_px = scan.camera->intrinsics().x();
  const double parallax_F_px = f_px * 1.5 * config.scan_step_m / config.foreground_depth_m;
  EXPECT_NEAR(d.foreground_flow_px, parallax_F_px, 0.05 * parallax_F_px);
  EXPECT_GT(d.foreground_flow_px, 1.3 * d.background_flow_px);
}

INSTANTIATE_TEST_SUITE_P(FiveShapes, Ts2pShapeTest, ::testing::ValuesIn(kTs2pShapes),
                         [](const auto& info) { return info.param; });

// Small openings at the mission's resolution (320 x 240, the `bench gapflyt` camera): a star, and
// an ellipse only 5 cm wider than the vehicle (0.43 m), each a few percent of the image. The
// wall's own spread of parallax (perspective across the view) is then larger than what the
// opening adds to a two-means split; the detection must still find the opening.
class Ts2pSmallOpeningTest : public ::testing::TestWithParam<std::string> {};

TEST_P(Ts2pSmallOpeningTest, DetectsASmallOpeningAtLowResolution) {
  Ts2pScanConfig config;
  config.width = 320;
  config.height = 240;
  config.seed = 5;
  config.scan_step_m = 0.06;  // 0.6 m/s at 30 Hz, stride 3: the mission's scan
  if (GetParam() == "tight") {
    config.shape = "ellipse";
    config.opening_size_m = Eigen::Vector2d(0.43, 0.8);
  } else {
    config.shape = GetParam();
  }
  sim::RayCaster caster;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  const perception::Ts2pDetection d = DetectAndScore(scan, GetParam());
  ASSERT_TRUE(d.valid);
  // The opening's mode is the background seen through it, below the wall's.
  EXPECT_LT(d.background_flow_px, d.foreground_flow_px);
}

INSTANTIATE_TEST_SUITE_P(StarAndTight, Ts2pSmallOpeningTest,
                         ::testing::Values("star", "triangle", "tight"),
                         [](const auto& info) { return info.param; });

// The hysteresis core (ts2p_detector.h, what the GapFlyt mission flies) on the mission's scans
// (320 x 240, 6 cm steps) of bench-drawn trials: narrowing O to its core must drop wall pixels
// called opening (the humps a vehicle aiming at O's centroid flies into) and keep the opening.
TEST(Ts2pCoreTest, TheCoreDropsWallAndKeepsTheOpening) {
  perception::Ts2pParams inclusive;
  perception::Ts2pParams core = inclusive;
  core.core_threshold_fraction = 0.6;
  perception::Ts2pDetector inclusive_detector(inclusive), core_detector(core);
  sim::RayCaster caster;
  double wall_inclusive = 0.0, wall_core = 0.0;
  int cores = 0;
  constexpr int kTrials = 15;  // three of each shape
  for (int trial = 0; trial < kTrials; ++trial) {
    Ts2pScanConfig config = DrawTs2pTrial(Ts2pTrialRanges{}, 3, trial);
    config.width = 320;
    config.height = 240;
    config.scan_step_m = 0.06;
    const Ts2pScan scan = RenderTs2pScan(config, caster);
    const perception::Ts2pDetection o = inclusive_detector.Detect(scan.reference, scan.frames);
    const perception::Ts2pDetection c = core_detector.Detect(scan.reference, scan.frames);
    ASSERT_EQ(o.valid, c.valid) << "trial " << trial;  // the decision is the inclusive one's
    if (!o.valid) continue;
    ASSERT_FALSE(o.core);
    cores += c.core;
    // The core lies inside O and keeps at least min_core_fraction of it.
    EXPECT_EQ(cv::countNonZero(c.opening & ~o.opening), 0) << "trial " << trial;
    EXPECT_GE(cv::countNonZero(c.opening), core.min_core_fraction * cv::countNonZero(o.opening));
    const perception::OpeningScore so = perception::ScoreOpening(o.opening, scan.truth);
    const perception::OpeningScore sc = perception::ScoreOpening(c.opening, scan.truth);
    EXPECT_GE(sc.overlap, 0.8) << "trial " << trial << " (" << config.shape << ")";
    wall_inclusive += so.false_positive;
    wall_core += sc.false_positive;
  }
  EXPECT_GE(cores, kTrials / 2);
  // Measured (seed 3): the core keeps 38 % of O's wall pixels, overlap >= 0.85 (O: >= 0.87).
  EXPECT_LT(wall_core, 0.5 * wall_inclusive) << wall_core << " vs " << wall_inclusive;
}

// The star's spikes show the smooth background wall through a few pixels: patch-based flow
// fills them from the wall's edge (F). The edge-aware refinement (step 3b) fills them from the
// similar-looking opening instead; without it the overlap drops towards seed 002's 0.75 limit.
TEST(Ts2pEdgeAwareTest, RecoversTheSpikesOfAStar) {
  Ts2pScanConfig config;
  config.shape = "star";
  config.seed = 11;
  sim::RayCaster caster;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  perception::Ts2pParams params;
  perception::Ts2pDetector refined(params);
  const perception::OpeningScore with =
      perception::ScoreOpening(refined.Detect(scan.reference, scan.frames).opening, scan.truth);
  params.edge_aware_lambda = 0.0;
  perception::Ts2pDetector raw(params);
  const perception::OpeningScore without =
      perception::ScoreOpening(raw.Detect(scan.reference, scan.frames).opening, scan.truth);
  EXPECT_GE(with.overlap, 0.9);
  EXPECT_LE(with.false_positive, 0.01);
  EXPECT_GT(with.overlap, without.overlap + 0.1);

  params.edge_aware_lambda = -1.0;
  EXPECT_THROW(perception::Ts2pDetector{params}, std::invalid_argument);
}

// Mean flow magnitude [px] over the pixels whose derotated ray stays in the frame.
double MeanFlowPx(const cv::Mat& flow, const cv::Mat& unseen) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < flow.rows; ++y) {
    for (int x = 0; x < flow.cols; ++x) {
      if (unseen.at<uchar>(y, x)) continue;
      const cv::Vec2f v = flow.at<cv::Vec2f>(y, x);
      sum += std::hypot(v[0], v[1]);
      ++count;
    }
  }
  return sum / count;
}

// A pure rotation (no baseline): the frame derotated through the camera model is the reference
// image again, so the flow between them is what derotation leaves (issue 13: < 0.1 px mean).
// DeepFlow measures it (0.017 px; its floor on two renders of one pose is 0.014 px). DIS-medium,
// the detector's flow, has a floor of ~0.2 px on that same-pose pair (sensor noise on the
// blank parts of the walls): derotation must add nothing beyond it.
TEST(Ts2pDerotationTest, PureRotationLeavesSubpixelResidual) {
  Ts2pScanConfig config;
  config.stack = 1;
  config.scan_step_m = 0.0;
  config.rotation_per_step_deg = Eigen::Vector3d(0.5, 1.0, 1.5);  // roll, pitch, yaw
  sim::RayCaster caster;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  config.rotation_per_step_deg.setZero();
  const Ts2pScan still = RenderTs2pScan(config, caster);  // same pose twice, own noise
  perception::Ts2pDetector detector(perception::Ts2pParams{}, scan.camera);
  cv::Mat unseen;
  const cv::Mat derotated = detector.Derotate(scan.frames[0], scan.R_CkCr[0], &unseen);
  // The rotation is large against the tolerance: ~9 px of rotational flow.
  EXPECT_GT(MeanFlowPx(detector.RotationalFlow(scan.R_CkCr[0]), unseen), 5.0);
  EXPECT_LT(cv::countNonZero(unseen), 0.1 * unseen.total());

  perception::DenseFlowParams accurate;
  accurate.method = "deepflow";
  EXPECT_LT(MeanFlowPx(perception::DenseFlow(accurate).Compute(scan.reference, derotated), unseen),
            0.1);
  perception::DenseFlow dis(perception::DenseFlowParams{});
  const double floor_px = MeanFlowPx(dis.Compute(still.reference, still.frames[0]), unseen);
  EXPECT_LT(MeanFlowPx(dis.Compute(scan.reference, derotated), unseen), floor_px + 0.05);

  // Without derotation the rotation looks like parallax; derotated, there is none to detect.
  const perception::Ts2pDetection raw = detector.Detect(scan.reference, scan.frames);
  EXPECT_GT(raw.foreground_flow_px, 5.0);
  const perception::Ts2pDetection d = detector.Detect(scan.reference, scan.frames, scan.R_CkCr);
  EXPECT_FALSE(d.valid) << d.status;
}

}  // namespace
}  // namespace aperture::experiments
