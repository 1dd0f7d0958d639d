// The LED front end on rendered infrared frames: emissive sim LEDs (radiometric fall-off, blob
// centroids at the projections) on the target's configuration, camera noise, occluders.
#include <gtest/gtest.h>

#include <cstdio>

#include "control/so3.h"
#include "perception/led/led_tracker.h"
#include "render_test_util.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"

namespace aperture::sim {
namespace {

using perception::LedConfiguration;
using perception::LedTracker;
using perception::LedTrackResult;
using perception::LedTrackStatus;

constexpr double kLedRadius_m = 0.01;
constexpr double kFocal_px = 420.0;  // MakeTestPinhole

// T_CT with the target facing the camera (z_T towards it), tilted by `tilt` (rotation vector in
// T) at position p_CT.
Eigen::Isometry3d TargetPose(const Eigen::Vector3d& p_CT, const Eigen::Vector3d& tilt) {
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.linear() =
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix() * control::ExpSo3(tilt);
  T_CT.translation() = p_CT;
  return T_CT;
}

// A point 20 cm in front of the LED at p_led_C, on its line of sight (a plate there hides it).
Eigen::Vector3d InFrontOf(const Eigen::Vector3d& p_led_C) {
  return p_led_C * (1.0 - 0.2 / p_led_C.norm());
}

double AngleError_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return control::LogSo3(a.linear() * b.linear().transpose()).norm() * 180.0 / M_PI;
}

class LedTrackerRenderTest : public ::testing::Test {
 protected:
  // Renders the target at T_CT (camera frame = world frame); every point of `occluders_C` adds a
  // 3 cm plate facing the camera there.
  cv::Mat Render(const Eigen::Isometry3d& T_CT, int frame_index,
                 const std::vector<Eigen::Vector3d>& occluders_C = {}) {
    Scene scene;
    // Peak of a resolved blob: intensity / (2 pi sigma^2) with sigma = 0.5 r f / d at 1 m
    // scaled: independent of distance. Aim at 0.8 of full scale (unsaturated).
    const double intensity = 0.8 * 2.0 * M_PI * std::pow(0.5 * kLedRadius_m * kFocal_px, 2);
    for (int i = 0; i < configuration_.size(); ++i) {
      SceneObject led;
      led.name = "led" + std::to_string(i);
      led.primitive = Led{kLedRadius_m, intensity, Rgb::Ones()};
      led.T_WO = testing::Pose({0, 0, 0}, T_CT * configuration_.p_T()[i]);
      scene.AddObject(led);
    }
    // A wall behind the target: the dim infrared background the detector has to ignore.
    scene.AddObject({"wall", Rectangle{{20.0, 20.0}, {}, {}}, {},
                     testing::Pose({0, 0, 0}, {0.0, 0.0, T_CT.translation().z() + 1.5})});
    for (std::size_t i = 0; i < occluders_C.size(); ++i) {
      scene.AddObject({"plate" + std::to_string(i), Rectangle{{0.03, 0.03}, {}, {}}, {},
                       testing::Pose({0, 0, 0}, occluders_C[i])});
    }
    CameraEffectsParams params;
    params.infrared = true;
    params.read_noise_sigma = 0.004;  // ~1 gray level
    params.seed = 3;
    return CameraEffects(params)
        .Capture(caster_, scene, *camera_,
                 [](double) { return Eigen::Isometry3d::Identity(); }, 0.0, frame_index)
        .frame.image;
  }

  std::shared_ptr<const perception::CameraModel> camera_ = testing::MakeTestPinhole();
  LedConfiguration configuration_ = LedConfiguration::Default();
  RayCaster caster_;
};

TEST_F(LedTrackerRenderTest, AccurateFromOneToTwoMetres) {
  double position_sum = 0.0, angle_sum = 0.0, position_worst = 0.0;
  int frames = 0;
  for (int k = 0; k < 8; ++k) {
    const double distance = 1.0 + k / 7.0;
    const Eigen::Isometry3d T_CT = TargetPose(
        {0.25 * std::sin(1.3 * k), 0.15 * std::cos(0.9 * k), distance},
        {0.4 * std::sin(0.7 * k + 1.0), 0.4 * std::cos(1.1 * k), 0.8 * k});
    LedTracker tracker(configuration_, camera_);  // fresh: brute-force correspondences
    const LedTrackResult result = tracker.Track(Render(T_CT, k), 0.0);
    ASSERT_TRUE(result.has_pose()) << "pose " << k << ": "
                                   << perception::LedTrackStatusName(result.status);
    EXPECT_EQ(result.status, LedTrackStatus::kReinitialized);
    const double position_error = (result.T_CT->translation() - T_CT.translation()).norm();
    position_sum += position_error;
    position_worst = std::max(position_worst, position_error);
    angle_sum += AngleError_deg(*result.T_CT, T_CT);
    ++frames;
  }
  std::printf("rendered 1-2 m: mean position error %.2f mm (worst %.2f mm), mean orientation "
              "error %.3f deg\n",
              1e3 * position_sum / frames, 1e3 * position_worst, angle_sum / frames);
  // Brief: mean position error <= 0.5 cm, mean orientation error <= 0.5 deg.
  EXPECT_LE(position_sum / frames, 0.005);
  EXPECT_LE(angle_sum / frames, 0.5);
}

TEST_F(LedTrackerRenderTest, CloseRangeAtThirtyCentimetres) {
  const Eigen::Isometry3d T_CT = TargetPose({0.01, -0.02, 0.3}, {0.15, -0.1, 0.4});
  LedTracker tracker(configuration_, camera_);
  const LedTrackResult result = tracker.Track(Render(T_CT, 0), 0.0);
  ASSERT_TRUE(result.has_pose()) << perception::LedTrackStatusName(result.status);
  const double position_error = (result.T_CT->translation() - T_CT.translation()).norm();
  std::printf("rendered 0.3 m: position error %.2f mm, orientation error %.3f deg\n",
              1e3 * position_error, AngleError_deg(*result.T_CT, T_CT));
  // Large blobs (sigma ~7 px) but the target fills the image: sub-millimetre expected.
  EXPECT_LT(position_error, 0.002);
  EXPECT_LT(AngleError_deg(*result.T_CT, T_CT), 0.5);
}

TEST_F(LedTrackerRenderTest, OccludingOneOfFiveLedsKeepsThePoseWithoutJumps) {
  LedTracker tracker(configuration_, camera_);
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d previous_truth = Eigen::Isometry3d::Identity();
  int occluded_frames_with_pose = 0;
  for (int k = 0; k < 10; ++k) {
    // 5 mm and 0.5 deg per frame sideways.
    const Eigen::Isometry3d T_CT =
        TargetPose({-0.05 + 0.005 * k, 0.02, 1.4}, {0.2, -0.1, 0.3 + 0.01 * k});
    std::vector<Eigen::Vector3d> occluders;
    if (k >= 4) occluders.push_back(InFrontOf(T_CT * configuration_.p_T()[2]));
    const LedTrackResult result = tracker.Track(Render(T_CT, k, occluders), 0.05 * k);
    ASSERT_TRUE(result.has_pose()) << "frame " << k << ": "
                                   << perception::LedTrackStatusName(result.status);
    if (k >= 4) {
      EXPECT_EQ(result.correspondences.size(), 4u) << "frame " << k;
      ++occluded_frames_with_pose;
    }
    if (k > 0) {
      // The estimate may move by the true motion (5 mm) plus the estimation error: a jump
      // larger than 2 cm (brief) would mean a wrong correspondence.
      const Eigen::Vector3d estimated_step = result.T_CT->translation() - previous.translation();
      const Eigen::Vector3d true_step = T_CT.translation() - previous_truth.translation();
      EXPECT_LT((estimated_step - true_step).norm(), 0.02) << "frame " << k;
    }
    EXPECT_LT((result.T_CT->translation() - T_CT.translation()).norm(), 0.01) << "frame " << k;
    previous = *result.T_CT;
    previous_truth = T_CT;
  }
  EXPECT_EQ(occluded_frames_with_pose, 6);
}

TEST_F(LedTrackerRenderTest, OccludingTwoOfFiveLedsKeepsThePoseFromThree) {
  // Issue 22: while tracking, plates hide LEDs 0 and 3 from frame 4 on; the three left give the
  // pose through P3P near the prediction, on the right LEDs and without jumps.
  LedTracker tracker(configuration_, camera_);
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d previous_truth = Eigen::Isometry3d::Identity();
  int three_led_frames = 0;
  for (int k = 0; k < 10; ++k) {
    // 5 mm and 0.5 deg per frame sideways.
    const Eigen::Isometry3d T_CT =
        TargetPose({-0.05 + 0.005 * k, 0.02, 1.4}, {0.2, -0.1, 0.3 + 0.01 * k});
    std::vector<Eigen::Vector3d> occluders;
    if (k >= 4) {
      for (const int led : {0, 3}) occluders.push_back(InFrontOf(T_CT * configuration_.p_T()[led]));
    }
    const LedTrackResult result = tracker.Track(Render(T_CT, k, occluders), 0.05 * k);
    ASSERT_TRUE(result.has_pose()) << "frame " << k << ": "
                                   << perception::LedTrackStatusName(result.status);
    if (k >= 4) {
      EXPECT_EQ(result.status, LedTrackStatus::kTrackedNearPrediction) << "frame " << k;
      ASSERT_EQ(result.correspondences.size(), 3u) << "frame " << k;
      for (const perception::LedCorrespondence& c : result.correspondences) {
        EXPECT_TRUE(c.led == 1 || c.led == 2 || c.led == 4) << "frame " << k;
      }
      ++three_led_frames;
    }
    if (k > 0) {
      // As with one LED hidden: a jump beyond 2 cm would mean a wrong labelling.
      const Eigen::Vector3d estimated_step = result.T_CT->translation() - previous.translation();
      const Eigen::Vector3d true_step = T_CT.translation() - previous_truth.translation();
      EXPECT_LT((estimated_step - true_step).norm(), 0.02) << "frame " << k;
    }
    // Three rendered blobs (centroid noise ~0.05 px) at 1.4 m: within 1 cm and 1 deg.
    EXPECT_LT((result.T_CT->translation() - T_CT.translation()).norm(), 0.01) << "frame " << k;
    EXPECT_LT(AngleError_deg(*result.T_CT, T_CT), 1.0) << "frame " << k;
    previous = *result.T_CT;
    previous_truth = T_CT;
  }
  EXPECT_EQ(three_led_frames, 6);
}

TEST_F(LedTrackerRenderTest, MergedLedsGiveNoConfidentWrongPose) {
  // The camera on the line through LEDs 3 and 4: their blobs merge into one.
  const Eigen::Vector3d u = (configuration_.p_T()[4] - configuration_.p_T()[3]).normalized();
  const Eigen::Vector3d p_TC = configuration_.p_T()[4] + 1.3 * u;
  const Eigen::Vector3d z = -p_TC.normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitY()).normalized();
  Eigen::Isometry3d T_TC = Eigen::Isometry3d::Identity();
  T_TC.linear() << x, z.cross(x), z;
  T_TC.translation() = p_TC;
  const Eigen::Isometry3d T_CT = T_TC.inverse();
  Eigen::Vector2d px3, px4;
  ASSERT_TRUE(camera_->Project(T_CT * configuration_.p_T()[3], &px3));
  ASSERT_TRUE(camera_->Project(T_CT * configuration_.p_T()[4], &px4));
  ASSERT_LT((px3 - px4).norm(), 1.0);
  // Fresh tracker on the merged frame, then a tracked sequence turning into the merge (3 deg
  // per frame about x_C through the target: LEDs 3 and 4 approach from ~8 px apart).
  auto check = [&](const LedTrackResult& result, const Eigen::Isometry3d& truth,
                   const std::string& label) {
    std::printf("merged LEDs (%s): %s, %zu blobs\n", label.c_str(),
                perception::LedTrackStatusName(result.status).c_str(), result.detections.size());
    if (result.has_pose()) {
      // Any pose given must be right within its own uncertainty (3 sigma, at least 5 mm).
      const double sigma = std::sqrt(result.covariance->topLeftCorner<3, 3>().trace());
      EXPECT_LT((result.T_CT->translation() - truth.translation()).norm(),
                std::max(0.005, 3.0 * sigma))
          << label;
    } else {
      EXPECT_TRUE(result.status == LedTrackStatus::kAmbiguous ||
                  result.status == LedTrackStatus::kNoCorrespondences ||
                  result.status == LedTrackStatus::kInconsistent)
          << label << ": " << perception::LedTrackStatusName(result.status);
    }
  };
  check(LedTracker(configuration_, camera_).Track(Render(T_CT, 0), 0.0), T_CT, "fresh");
  LedTracker tracker(configuration_, camera_);
  int poses = 0;
  for (int k = 0; k <= 5; ++k) {
    const double angle = (15.0 - 3.0 * k) * M_PI / 180.0;
    Eigen::Isometry3d T_CT_k = T_CT;
    T_CT_k.linear() =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix() * T_CT.linear();
    T_CT_k.translation() =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix() *
            (T_CT.translation() - Eigen::Vector3d(0, 0, T_CT.translation().z())) +
        Eigen::Vector3d(0, 0, T_CT.translation().z());
    const LedTrackResult result = tracker.Track(Render(T_CT_k, k + 1), 0.05 * k);
    poses += result.has_pose() ? 1 : 0;
    check(result, T_CT_k, "tracking, " + std::to_string(15 - 3 * k) + " deg");
  }
  EXPECT_GE(poses, 2);  // tracked while the LEDs were apart
}

}  // namespace
}  // namespace aperture::sim
