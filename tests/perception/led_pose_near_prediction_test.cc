#include "perception/led/led_pose_near_prediction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/led/led_configuration.h"

namespace aperture::perception {
namespace {

constexpr double kFocal_px = 420.0;

class LedPoseNearPredictionTest : public ::testing::Test {
 protected:
  // The built-in target 1.3 m in front of the camera, turned so no two LED images are close.
  const Eigen::Isometry3d T_CT_true_ =
      control::ExpSe3((control::Vector6d() << -0.1, 0.05, 1.3, 0.3, -0.2, 0.1).finished());

  // Exact detections of the LEDs not in `hidden` at T_CT, in LED order.
  std::vector<LedDetection> Detections(const Eigen::Isometry3d& T_CT,
                                       const std::vector<int>& hidden) const {
    std::vector<LedDetection> detections;
    for (int led = 0; led < configuration_.size(); ++led) {
      if (std::find(hidden.begin(), hidden.end(), led) != hidden.end()) continue;
      LedDetection detection;
      EXPECT_TRUE(camera_->Project(T_CT * configuration_.p_T()[led], &detection.px));
      detection.f_C = camera_->Unproject(detection.px);
      detections.push_back(detection);
    }
    return detections;
  }
  std::vector<int> Visible(const std::vector<int>& hidden) const {
    std::vector<int> visible;
    for (int led = 0; led < configuration_.size(); ++led) {
      if (std::find(hidden.begin(), hidden.end(), led) == hidden.end()) visible.push_back(led);
    }
    return visible;
  }
  static double AngleBetween(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return control::LogSo3(a.linear() * b.linear().transpose()).norm();
  }

  std::shared_ptr<const CameraModel> camera_ = std::make_shared<PinholeCamera>(
      752, 480, PinholeIntrinsics{kFocal_px, kFocal_px, 375.5, 239.5});
  LedConfiguration configuration_ = LedConfiguration::Default();
  LedCorrespondenceParams correspondence_;
};

TEST_F(LedPoseNearPredictionTest, ImageDistanceOfATranslationIsFocalTimesShiftOverNearestDepth) {
  // Pinhole: moving every LED by delta along x_C moves its image by f delta / z_C; the largest
  // move is the nearest LED's.
  const double delta_m = 0.004;
  Eigen::Isometry3d shifted = T_CT_true_;
  shifted.translation().x() += delta_m;
  double nearest_z = 1e9;
  for (const Eigen::Vector3d& p_T : configuration_.p_T()) {
    nearest_z = std::min(nearest_z, (T_CT_true_ * p_T).z());
  }
  EXPECT_NEAR(LedImageDistance(*camera_, configuration_.p_T(), T_CT_true_, shifted),
              kFocal_px * delta_m / nearest_z, 1e-9);
  EXPECT_EQ(LedImageDistance(*camera_, configuration_.p_T(), T_CT_true_, T_CT_true_), 0.0);
}

TEST_F(LedPoseNearPredictionTest, ThreeLedsNearThePredictionGiveTheTruePoseForEveryHiddenPair) {
  // The prediction off by ~2 mm and 0.2 deg (a constant-velocity prediction's error at 50 Hz):
  // P3P on the three visible LEDs, every labelling, must come back to the true labelling and
  // pose.
  const Eigen::Isometry3d T_CT_predicted =
      control::ExpSe3(
          (control::Vector6d() << 0.002, -0.001, 0.001, 0.003, 0.0, -0.002).finished()) *
      T_CT_true_;
  for (int a = 0; a < configuration_.size(); ++a) {
    for (int b = a + 1; b < configuration_.size(); ++b) {
      const std::vector<int> hidden{a, b};
      const LedNearPredictionResult result =
          FindLedPoseNearPrediction(configuration_.p_T(), Detections(T_CT_true_, hidden), *camera_,
                                    T_CT_predicted, correspondence_);
      ASSERT_EQ(result.status, LedNearPredictionStatus::kFound)
          << "hidden " << a << ", " << b << ": " << LedNearPredictionStatusName(result.status);
      const std::vector<int> visible = Visible(hidden);
      ASSERT_EQ(result.correspondences.size(), 3u);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(result.correspondences[k].led, visible[k]);
        EXPECT_EQ(result.correspondences[k].detection, k);  // detections are in LED order
      }
      // Exact bearings: P3P is exact up to the quartic's round-off.
      EXPECT_LT((result.T_CT->translation() - T_CT_true_.translation()).norm(), 1e-6);
      EXPECT_LT(AngleBetween(*result.T_CT, T_CT_true_), 1e-6);
      EXPECT_LE(result.distance_px, LedNearPredictionParams{}.gate_px);
      // 60 ordered LED triples, up to 4 solutions each.
      EXPECT_GT(result.pose_candidates, 60);
    }
  }
}

TEST_F(LedPoseNearPredictionTest, EveryWrongAssignmentAndMirrorSolutionFailsTheGate) {
  // The gate is what rejects them: for three detections, every P3P solution of every labelling
  // but the true one moves some LED's image by more than gate_px from the (here exact)
  // prediction.
  const double gate_px = LedNearPredictionParams{}.gate_px;
  const std::vector<int> hidden{1, 3};
  const std::vector<LedDetection> detections = Detections(T_CT_true_, hidden);
  const std::vector<int> visible = Visible(hidden);
  std::array<Eigen::Vector3d, 3> f_C{detections[0].f_C, detections[1].f_C, detections[2].f_C};
  std::vector<Eigen::Isometry3d> solutions;
  int wrong_solutions = 0, true_solutions_in_gate = 0;
  const int n = configuration_.size();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int l = 0; l < n; ++l) {
        if (i == j || j == l || i == l) continue;
        const bool true_labelling = i == visible[0] && j == visible[1] && l == visible[2];
        SolveP3p(correspondence_.p3p_method, f_C,
                 {configuration_.p_T()[i], configuration_.p_T()[j], configuration_.p_T()[l]},
                 &solutions);
        for (const Eigen::Isometry3d& T_CT : solutions) {
          const double distance =
              LedImageDistance(*camera_, configuration_.p_T(), T_CT, T_CT_true_);
          const bool is_truth = (T_CT.translation() - T_CT_true_.translation()).norm() < 1e-6;
          if (true_labelling && is_truth) {
            EXPECT_LT(distance, 1e-3);
            ++true_solutions_in_gate;
            continue;
          }
          ++wrong_solutions;
          EXPECT_GT(distance, gate_px) << "labelling " << i << j << l;
        }
      }
    }
  }
  EXPECT_EQ(true_solutions_in_gate, 1);
  EXPECT_GT(wrong_solutions, 59);  // every other labelling has at least one real solution
}

TEST_F(LedPoseNearPredictionTest, APredictionFarFromTheTruthFindsNothing) {
  // 3 cm sideways at 1.3 m moves every image by ~10 px, twice the gate; a 15 deg turn of the
  // target about x_C moves an LED 10 cm from its centre by up to ~8 px (asserted below).
  const std::vector<LedDetection> detections = Detections(T_CT_true_, {0, 4});
  Eigen::Isometry3d shifted = T_CT_true_;
  shifted.translation().x() += 0.03;
  Eigen::Isometry3d turned = T_CT_true_;
  turned.linear() =
      Eigen::AngleAxisd(15.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) * T_CT_true_.linear();
  for (const Eigen::Isometry3d& prediction : {shifted, turned}) {
    ASSERT_GT(LedImageDistance(*camera_, configuration_.p_T(), prediction, T_CT_true_),
              LedNearPredictionParams{}.gate_px);
    const LedNearPredictionResult result = FindLedPoseNearPrediction(
        configuration_.p_T(), detections, *camera_, prediction, correspondence_);
    EXPECT_EQ(result.status, LedNearPredictionStatus::kNoCandidateInGate);
    EXPECT_FALSE(result.T_CT.has_value());
    EXPECT_EQ(result.candidates_in_gate, 0);
  }
}

TEST_F(LedPoseNearPredictionTest, AFourthDetectionIsExplainedAndAFalseOneIgnored) {
  // Four real LEDs plus a false blob: the candidate explaining four wins over any candidate from
  // a subset with the false blob, and the false blob gets no LED.
  std::vector<LedDetection> detections = Detections(T_CT_true_, {2});
  LedDetection false_blob;
  false_blob.px = Eigen::Vector2d(600.0, 60.0);
  false_blob.f_C = camera_->Unproject(false_blob.px);
  detections.push_back(false_blob);
  const LedNearPredictionResult result = FindLedPoseNearPrediction(
      configuration_.p_T(), detections, *camera_, T_CT_true_, correspondence_);
  ASSERT_EQ(result.status, LedNearPredictionStatus::kFound);
  ASSERT_EQ(result.correspondences.size(), 4u);
  for (const LedCorrespondence& c : result.correspondences) {
    EXPECT_NE(c.led, 2);
    EXPECT_NE(c.detection, 4);
  }
}

TEST_F(LedPoseNearPredictionTest, TwoLedImagesWithinTheGateOfEachOtherAreAmbiguous) {
  // The camera 1.3 m beyond LED 4 on the line from LED 3 through LED 4, moved 10 cm off that
  // line: the two images lie ~3 px apart, so swapping their labels moves every LED's image by
  // only a few px, inside the gate. Three detections (LEDs 0, 3, 4): the search must not choose.
  const Eigen::Vector3d p3 = configuration_.p_T()[3], p4 = configuration_.p_T()[4];
  const Eigen::Vector3d u = (p4 - p3).normalized();
  const Eigen::Vector3d off_line = u.cross(Eigen::Vector3d::UnitX()).normalized();
  const Eigen::Vector3d p_TC = p4 + 1.3 * u + 0.1 * off_line;
  const Eigen::Vector3d z = -p_TC.normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitY()).normalized();
  Eigen::Isometry3d T_TC = Eigen::Isometry3d::Identity();
  T_TC.linear() << x, z.cross(x), z;
  T_TC.translation() = p_TC;
  const Eigen::Isometry3d T_CT = T_TC.inverse();
  const std::vector<LedDetection> detections = Detections(T_CT, {1, 2});
  const double separation_px = (detections[1].px - detections[2].px).norm();
  ASSERT_GT(separation_px, 1.0);
  ASSERT_LT(separation_px, LedNearPredictionParams{}.gate_px);
  const LedNearPredictionResult result =
      FindLedPoseNearPrediction(configuration_.p_T(), detections, *camera_, T_CT, correspondence_);
  EXPECT_EQ(result.status, LedNearPredictionStatus::kAmbiguous)
      << LedNearPredictionStatusName(result.status) << ", images " << separation_px << " px apart";
  EXPECT_FALSE(result.T_CT.has_value());
}

TEST_F(LedPoseNearPredictionTest, FewerThanThreeDetectionsFindNothing) {
  const LedNearPredictionResult result =
      FindLedPoseNearPrediction(configuration_.p_T(), Detections(T_CT_true_, {0, 1, 2}), *camera_,
                                T_CT_true_, correspondence_);
  EXPECT_EQ(result.status, LedNearPredictionStatus::kTooFewDetections);
  EXPECT_EQ(result.pose_candidates, 0);
}

}  // namespace
}  // namespace aperture::perception
