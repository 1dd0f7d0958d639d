#include "perception/led/led_tracker.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "control/so3.h"
#include "led_test_images.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::perception {
namespace {

class LedTrackerTest : public ::testing::Test {
 protected:
  // The target moving linearly in twist coordinates, the model of (C.6): ~0.2 m/s, 0.5 rad/s.
  Eigen::Isometry3d PoseAt(double t_s) const {
    const control::Vector6d xi_0 =
        (control::Vector6d() << -0.1, 0.05, 1.3, 0.3, -0.2, 0.1).finished();
    const control::Vector6d xi_dot =
        (control::Vector6d() << 0.2, 0.0, 0.0, 0.5, 0.0, 0.0).finished();
    return control::ExpSe3(xi_0 + t_s * xi_dot);
  }
  std::vector<Eigen::Vector2d> Projections(const Eigen::Isometry3d& T_CT) const {
    std::vector<Eigen::Vector2d> px;
    for (const auto& p_T : configuration_.p_T()) {
      px.emplace_back();
      EXPECT_TRUE(camera_->Project(T_CT * p_T, &px.back()));
    }
    return px;
  }

  std::shared_ptr<const CameraModel> camera_ =
      std::make_shared<PinholeCamera>(752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
  LedConfiguration configuration_ = LedConfiguration::Default();
};

TEST_F(LedTrackerTest, InitializesByBruteForceThenTracksWithPredictionInRois) {
  LedTracker tracker(configuration_, camera_);
  for (int k = 0; k < 10; ++k) {
    const double t_s = 0.02 * k;
    const cv::Mat image =
        test_support::BlobImage(752, 480, Projections(PoseAt(t_s)), /*sigma_px=*/2.0);
    const LedTrackResult result = tracker.Track(image, t_s);
    ASSERT_TRUE(result.has_pose()) << "frame " << k << " " << LedTrackStatusName(result.status);
    EXPECT_EQ(result.status, k == 0 ? LedTrackStatus::kReinitialized : LedTrackStatus::kTracked);
    EXPECT_EQ(result.used_roi, k > 0);
    EXPECT_EQ(result.correspondences.size(), 5u);
    // Centroids within ~0.05 px give millimetre poses at 1.3 m.
    EXPECT_LT((result.T_CT->translation() - PoseAt(t_s).translation()).norm(), 0.003);
    ASSERT_TRUE(result.covariance.has_value());
    EXPECT_GT(result.covariance->diagonal().minCoeff(), 0.0);
  }
  // (C.6), (C.7) extrapolate the estimated poses of 0.16 s and 0.18 s to 0.2 s: their ~2 mm
  // errors at most triple, far inside the 5 px (~1.5 cm at 1.3 m) matching gate.
  const auto predicted = tracker.Predict(0.2);
  ASSERT_TRUE(predicted.has_value());
  EXPECT_LT((predicted->translation() - PoseAt(0.2).translation()).norm(), 0.006);
}

TEST_F(LedTrackerTest, FreshStartWithFourOfFiveLedsFindsTheTruePose) {
  // Each LED hidden in turn, with and without a false bright spot: the brute force alone (no
  // prior pose) must find the four visible LEDs and the true pose (thesis C.4.2: four LEDs fix
  // the pose).
  for (int hidden = 0; hidden < configuration_.size(); ++hidden) {
    for (const bool false_spot : {false, true}) {
      std::vector<Eigen::Vector2d> px = Projections(PoseAt(0.0));
      px.erase(px.begin() + hidden);
      if (false_spot) px.emplace_back(610.0, 80.0);
      LedTracker tracker(configuration_, camera_);
      const LedTrackResult result = tracker.Track(test_support::BlobImage(752, 480, px, 2.0), 0.0);
      ASSERT_TRUE(result.has_pose()) << "LED " << hidden << " hidden, false spot " << false_spot
                                     << ": " << LedTrackStatusName(result.status);
      EXPECT_EQ(result.status, LedTrackStatus::kReinitialized);
      EXPECT_EQ(result.correspondences.size(), 4u);
      for (const LedCorrespondence& c : result.correspondences) EXPECT_NE(c.led, hidden);
      // Four centroids within ~0.05 px still give millimetre poses at 1.3 m.
      EXPECT_LT((result.T_CT->translation() - PoseAt(0.0).translation()).norm(), 0.003);
      EXPECT_LT(Eigen::AngleAxisd(result.T_CT->linear().transpose() * PoseAt(0.0).linear()).angle(),
                0.01);
    }
  }
}

// Images of the LEDs not in `hidden` at T_CT (blob sigma 2 px).
cv::Mat ImageWithout(const std::vector<Eigen::Vector2d>& px, const std::vector<int>& hidden) {
  std::vector<Eigen::Vector2d> shown;
  for (int led = 0; led < static_cast<int>(px.size()); ++led) {
    if (std::find(hidden.begin(), hidden.end(), led) == hidden.end()) shown.push_back(px[led]);
  }
  return test_support::BlobImage(752, 480, shown, /*sigma_px=*/2.0);
}

TEST_F(LedTrackerTest, TwoHiddenLedsKeepThePoseFromThreeWhileTracking) {
  // Tracked on five LEDs, then LEDs 1 and 3 hidden: the three left give the pose through P3P
  // near the prediction (issue 22), with the right LEDs and millimetre errors; when the LEDs
  // come back the tracker is on the four-LED path again.
  LedTracker tracker(configuration_, camera_);
  for (int k = 0; k < 12; ++k) {
    const double t_s = 0.02 * k;
    const bool hidden = k >= 3 && k < 9;
    const LedTrackResult result =
        tracker.Track(ImageWithout(Projections(PoseAt(t_s)),
                                   hidden ? std::vector<int>{1, 3} : std::vector<int>{}),
                      t_s);
    ASSERT_TRUE(result.has_pose()) << "frame " << k << " " << LedTrackStatusName(result.status);
    if (!hidden) {
      EXPECT_NE(result.status, LedTrackStatus::kTrackedNearPrediction) << "frame " << k;
      continue;
    }
    EXPECT_EQ(result.status, LedTrackStatus::kTrackedNearPrediction) << "frame " << k;
    EXPECT_TRUE(result.used_near_prediction);
    EXPECT_FALSE(result.used_brute_force);
    ASSERT_EQ(result.correspondences.size(), 3u);
    EXPECT_EQ(result.correspondences[0].led, 0);
    EXPECT_EQ(result.correspondences[1].led, 2);
    EXPECT_EQ(result.correspondences[2].led, 4);
    // Three centroids within ~0.05 px fix the pose to a few mm at 1.3 m (P3P is exact; the
    // error is the centroids', amplified by the weaker geometry of three points).
    EXPECT_LT((result.T_CT->translation() - PoseAt(t_s).translation()).norm(), 0.005)
        << "frame " << k;
    EXPECT_LT(Eigen::AngleAxisd(result.T_CT->linear().transpose() * PoseAt(t_s).linear()).angle(),
              0.01)
        << "frame " << k;
    EXPECT_GT(result.stage_times.near_prediction_s, 0.0);
  }
}

TEST_F(LedTrackerTest, FreshStartWithThreeLedsGivesNoPose) {
  // Without a prediction three LEDs do not choose among P3P's labellings: no pose, whichever
  // two are hidden.
  for (int a = 0; a < configuration_.size(); ++a) {
    for (int b = a + 1; b < configuration_.size(); ++b) {
      LedTracker tracker(configuration_, camera_);
      const LedTrackResult result =
          tracker.Track(ImageWithout(Projections(PoseAt(0.0)), {a, b}), 0.0);
      EXPECT_FALSE(result.has_pose()) << "hidden " << a << ", " << b;
      EXPECT_FALSE(result.used_near_prediction);
    }
  }
}

TEST_F(LedTrackerTest, ThreeLedsFarFromThePredictionGiveNoPose) {
  // Tracked at rest, then the target jumps 4 cm sideways (~13 px at 1.3 m, beyond the 5 px
  // gate) with two LEDs hidden: the P3P candidates of the three left are all far from the
  // prediction, so the frame has no pose instead of a jump to a pose the prediction did not
  // choose.
  LedTracker tracker(configuration_, camera_);
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(tracker.Track(ImageWithout(Projections(PoseAt(0.0)), {}), 0.02 * k).has_pose());
  }
  Eigen::Isometry3d jumped = PoseAt(0.0);
  jumped.translation().x() += 0.04;
  const LedTrackResult result = tracker.Track(ImageWithout(Projections(jumped), {0, 2}), 0.06);
  EXPECT_FALSE(result.has_pose()) << LedTrackStatusName(result.status);
  EXPECT_TRUE(result.used_near_prediction);
}

TEST_F(LedTrackerTest, ThreeLedPosesLooserThanTheRotationSigmaBoundAreRejected) {
  // Three LEDs at 1.3 m fix the rotation to ~2 deg at 1 px (C.9): with the bound below that the
  // covariance check rejects the pose near the prediction, with the default bound it passes.
  for (const double bound_deg : {1.0, LedTrackerParams{}.max_near_prediction_rotation_sigma_deg}) {
    LedTrackerParams params;
    params.max_near_prediction_rotation_sigma_deg = bound_deg;
    LedTracker tracker(configuration_, camera_, params);
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(
          tracker.Track(ImageWithout(Projections(PoseAt(0.02 * k)), {}), 0.02 * k).has_pose());
    }
    const LedTrackResult result =
        tracker.Track(ImageWithout(Projections(PoseAt(0.06)), {1, 3}), 0.06);
    EXPECT_TRUE(result.used_near_prediction);
    EXPECT_EQ(result.has_pose(), bound_deg > 1.0) << bound_deg << " deg";
  }
}

TEST_F(LedTrackerTest, ReportsStageTimes) {
  LedTracker tracker(configuration_, camera_);
  const cv::Mat image = test_support::BlobImage(752, 480, Projections(PoseAt(0.0)), 2.0);
  const LedStageTimes first = tracker.Track(image, 0.0).stage_times;
  EXPECT_GT(first.detection_s, 0.0);
  EXPECT_GT(first.brute_force_s, 0.0);
  EXPECT_GT(first.refinement_s, 0.0);
  const LedStageTimes second = tracker.Track(image, 0.02).stage_times;
  EXPECT_GT(second.prediction_s, 0.0);
  EXPECT_EQ(second.brute_force_s, 0.0);  // tracked: no brute force
}

// Table C.2's timing protocol: brute force on the full image in every frame, the prediction still
// computed from the poses before (and timed), the poses as good as tracking's.
TEST_F(LedTrackerTest, ForcedBruteForceLabelsEveryFrameAndStillPredicts) {
  LedTrackerParams params;
  params.force_brute_force = true;
  LedTracker tracker(configuration_, camera_, params);
  for (int k = 0; k < 5; ++k) {
    const double t_s = 0.02 * k;
    const LedTrackResult result =
        tracker.Track(test_support::BlobImage(752, 480, Projections(PoseAt(t_s)), 2.0), t_s);
    ASSERT_TRUE(result.has_pose()) << "frame " << k << " " << LedTrackStatusName(result.status);
    EXPECT_EQ(result.status, LedTrackStatus::kReinitialized) << k;
    EXPECT_TRUE(result.used_brute_force) << k;
    EXPECT_FALSE(result.used_roi) << k;
    EXPECT_GT(result.stage_times.brute_force_s, 0.0) << k;
    EXPECT_LT((result.T_CT->translation() - PoseAt(t_s).translation()).norm(), 0.003) << k;
  }
  // The history of poses is kept: (C.6) extrapolates the last two brute-force poses.
  const auto predicted = tracker.Predict(0.1);
  ASSERT_TRUE(predicted.has_value());
  EXPECT_LT((predicted->translation() - PoseAt(0.1).translation()).norm(), 0.006);
}

TEST_F(LedTrackerTest, PredictionFollowsEquationC6) {
  LedTracker tracker(configuration_, camera_);
  EXPECT_FALSE(tracker.Predict(0.0).has_value());
  ASSERT_TRUE(tracker.Track(test_support::BlobImage(752, 480, Projections(PoseAt(0.0)), 2.0), 0.0)
                  .has_pose());
  // n_P = 1: Delta T = 0, the last pose.
  const Eigen::Isometry3d first = *tracker.Predict(0.02);
  const LedTrackResult tracked =
      tracker.Track(test_support::BlobImage(752, 480, Projections(PoseAt(0.02)), 2.0), 0.02);
  ASSERT_EQ(tracked.status, LedTrackStatus::kTracked);
  const Eigen::Isometry3d second = *tracker.Predict(0.05);
  // xi = xi_1 + (0.05 - 0.02) / (0.02 - 0.0) (xi_1 - xi_0) with the estimated poses.
  const control::Vector6d expected =
      control::LogSe3(*tracked.T_CT) +
      1.5 * (control::LogSe3(*tracked.T_CT) - control::LogSe3(first));
  EXPECT_LT((control::LogSe3(second) - expected).cwiseAbs().maxCoeff(), 1e-9);
}

TEST_F(LedTrackerTest, NoDetectionsGiveNoPose) {
  LedTracker tracker(configuration_, camera_);
  const LedTrackResult result = tracker.Track(cv::Mat::zeros(480, 752, CV_8UC1), 0.0);
  EXPECT_FALSE(result.has_pose());
  EXPECT_EQ(result.status, LedTrackStatus::kNoDetections);
}

TEST_F(LedTrackerTest, FiftyFalseBlobsAreCappedWithAWarning) {
  std::vector<Eigen::Vector2d> centres;
  for (int i = 0; i < 50; ++i) centres.emplace_back(40.0 + 70.0 * (i % 10), 40.0 + 80.0 * (i / 10));
  LedTracker tracker(configuration_, camera_);
  const LedTrackResult result = tracker.Track(test_support::BlobImage(752, 480, centres, 2.0), 0.0);
  // The grid has no LED target in it: at most max_blobs detections reach the brute force
  // (bounded work) and the frame must not produce a pose.
  EXPECT_EQ(static_cast<int>(result.detections.size()), LedDetectorParams{}.max_blobs);
  EXPECT_THAT(result.warning, ::testing::HasSubstr("50 bright blobs"));
  EXPECT_FALSE(result.has_pose());
}

// Issue 21, Fig. C.7's outliers: a fresh start accepts a pose only when the second-best labelling
// fits clearly worse than the best (LedTrackerParams::labelling_margin_ratio). The target is 17 mm
// (worst LED, after the best rigid fit) from a 180 deg symmetry about z_T that swaps LEDs 0 <-> 1
// and 2 <-> 3: valid for LedConfiguration (tolerance 15 mm), but at 2.5 m the swapped labelling
// reprojects within ~3 px of the true one.
class LedTrackerLabellingMarginTest : public ::testing::Test {
 protected:
  static constexpr std::array<int, 4> kSwap{1, 0, 3, 2};

  // The true pose: facing the camera at 2.5 m, tilted 10 deg.
  Eigen::Isometry3d T_CT_true() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(0.05, -0.03, 2.5);
    return T;
  }
  // The true LEDs' projections.
  std::vector<Eigen::Vector2d> TrueProjections() const {
    std::vector<Eigen::Vector2d> px(4);
    for (int i = 0; i < 4; ++i) {
      EXPECT_TRUE(camera_->Project(T_CT_true() * configuration_.p_T()[i], &px[i]));
    }
    return px;
  }
  // Halfway between each true projection and the projection of its swapped LED with the target
  // at the pose that best fits the swapped labelling in 3D (Umeyama): both labellings explain
  // these blobs about equally well.
  std::vector<Eigen::Vector2d> AmbiguousProjections() const {
    Eigen::Matrix<double, 3, 4> swapped, original;
    for (int i = 0; i < 4; ++i) {
      swapped.col(i) = configuration_.p_T()[kSwap[i]];
      original.col(i) = configuration_.p_T()[i];
    }
    // S p_T[kSwap[i]] ~ p_T[i], so T_CT_true() S puts LED kSwap[i] where LED i is.
    const Eigen::Isometry3d S(Eigen::Matrix4d(Eigen::umeyama(swapped, original, false)));
    std::vector<Eigen::Vector2d> px = TrueProjections();
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector2d px_swapped;
      EXPECT_TRUE(camera_->Project(T_CT_true() * S * configuration_.p_T()[kSwap[i]], &px_swapped));
      px[i] = 0.5 * (px[i] + px_swapped);
    }
    return px;
  }

  std::shared_ptr<const CameraModel> camera_ =
      std::make_shared<PinholeCamera>(752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
  LedConfiguration configuration_{
      {{0.095, 0.0, 0.0}, {-0.06, 0.0, 0.0}, {0.0, 0.045, 0.03}, {0.0, -0.045, 0.03}},
      "near-symmetric test target"};
};

TEST_F(LedTrackerLabellingMarginTest, TwoLabellingsFittingAlikeGiveNoPose) {
  const cv::Mat image = test_support::BlobImage(752, 480, AmbiguousProjections(), 1.5);
  LedTracker tracker(configuration_, camera_);
  const LedTrackResult result = tracker.Track(image, 0.0);
  EXPECT_EQ(result.status, LedTrackStatus::kAmbiguous) << LedTrackStatusName(result.status);
  EXPECT_FALSE(result.has_pose());
  EXPECT_FALSE(result.covariance.has_value());
  EXPECT_LT(result.runner_up_rms_px, LedTrackerParams{}.labelling_margin_ratio * result.rms_px);
  // No pose was kept: the next frame starts afresh.
  EXPECT_FALSE(tracker.Predict(0.02).has_value());
  // Without the margin the same image gives a pose, both labellings within max_rms_px: the
  // margin is what rejects it.
  LedTrackerParams no_margin;
  no_margin.labelling_margin_ratio = 0.0;
  LedTracker unguarded(configuration_, camera_, no_margin);
  const LedTrackResult unguarded_result = unguarded.Track(image, 0.0);
  EXPECT_TRUE(unguarded_result.has_pose()) << LedTrackStatusName(unguarded_result.status);
  EXPECT_LE(unguarded_result.rms_px, LedTrackerParams{}.max_rms_px);
  EXPECT_LE(unguarded_result.runner_up_rms_px, LedTrackerParams{}.max_rms_px);
}

TEST_F(LedTrackerLabellingMarginTest, AClearLabellingGivesTheTruePose) {
  // The same target and pose, blobs at the true projections: the swapped labelling is off by
  // ~1.5 px per LED after refinement, the true one by the centroids' rounding.
  LedTracker tracker(configuration_, camera_);
  const LedTrackResult result =
      tracker.Track(test_support::BlobImage(752, 480, TrueProjections(), 1.5), 0.0);
  ASSERT_TRUE(result.has_pose()) << LedTrackStatusName(result.status);
  EXPECT_EQ(result.status, LedTrackStatus::kReinitialized);
  EXPECT_TRUE(std::isfinite(result.runner_up_rms_px));
  EXPECT_GE(result.runner_up_rms_px, LedTrackerParams{}.labelling_margin_ratio * result.rms_px);
  const Eigen::Isometry3d T_true = T_CT_true();
  EXPECT_LT(Eigen::AngleAxisd(result.T_CT->linear().transpose() * T_true.linear()).angle(),
            1.0 * M_PI / 180.0);
  EXPECT_LT((result.T_CT->translation() - T_true.translation()).norm(), 0.01);
}

}  // namespace
}  // namespace aperture::perception
