#include "perception/led/led_correspondence_search.h"

#include <gtest/gtest.h>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/led/led_configuration.h"

namespace aperture::perception {
namespace {

class LedCorrespondenceSearchTest : public ::testing::TestWithParam<P3pMethod> {
 protected:
  LedCorrespondenceSearchTest() {
    T_CT_ = control::ExpSe3((control::Vector6d() << 0, 0, 0, 0.4, 0.3, -0.2).finished());
    T_CT_.translation() = Eigen::Vector3d(-0.1, 0.05, 1.2);
  }
  // Detections of every LED in a shuffled order (detection d sees LED order_[d]).
  std::vector<LedDetection> Detect(const std::vector<int>& order) const {
    std::vector<LedDetection> detections;
    for (int led : order) {
      LedDetection detection;
      EXPECT_TRUE(camera_.Project(T_CT_ * configuration_.p_T()[led], &detection.px));
      detection.f_C = camera_.Unproject(detection.px);
      detections.push_back(detection);
    }
    return detections;
  }
  static LedDetection At(const PinholeCamera& camera, const Eigen::Vector2d& px) {
    LedDetection detection;
    detection.px = px;
    detection.f_C = camera.Unproject(px);
    return detection;
  }
  LedCorrespondenceParams Params() const {
    LedCorrespondenceParams params;
    params.p3p_method = GetParam();
    return params;
  }

  PinholeCamera camera_{752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5}};
  LedConfiguration configuration_ = LedConfiguration::Default();
  Eigen::Isometry3d T_CT_;
};

TEST_P(LedCorrespondenceSearchTest, HistogramPicksTheTrueCorrespondencesWithAnOutlier) {
  const std::vector<int> order{3, 0, 4, 1, 2};
  std::vector<LedDetection> detections = Detect(order);
  detections.insert(detections.begin() + 2, At(camera_, {600.0, 90.0}));  // a false blob
  LedCorrespondenceSearch search(configuration_.p_T(), Params());
  Eigen::MatrixXi histogram;
  const LedCorrespondenceResult result = search.FindByBruteForce(detections, camera_, &histogram);
  ASSERT_EQ(result.correspondences.size(), 5u);
  for (const LedCorrespondence& c : result.correspondences) {
    ASSERT_NE(c.detection, 2) << "the outlier was matched";
    const int d = c.detection > 2 ? c.detection - 1 : c.detection;
    EXPECT_EQ(order[d], c.led);
    // Ideal votes: C(5, 3) = 10 per true pair (Fig. C.5).
    EXPECT_GE(histogram(c.led, c.detection), 10);
  }
  // (C.5): 4 * C(6, 3) * 5! / 2! = 4800 candidates at most.
  EXPECT_LE(result.pose_candidates, 4800);
  EXPECT_GT(result.pose_candidates, 0);
  ASSERT_TRUE(result.T_CT.has_value());
  EXPECT_LT((result.T_CT->matrix() - T_CT_.matrix()).cwiseAbs().maxCoeff(), 1e-6);
}

TEST_P(LedCorrespondenceSearchTest, VerifyAcceptsTrueAndRejectsSwappedCorrespondences) {
  const std::vector<LedDetection> detections = Detect({0, 1, 2, 3, 4});
  LedCorrespondenceSearch search(configuration_.p_T(), Params());
  std::vector<LedCorrespondence> truth{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
  const LedCorrespondenceResult good = search.Verify(truth, detections, camera_);
  EXPECT_TRUE(good.verified);
  EXPECT_DOUBLE_EQ(good.verified_ratio, 1.0);
  ASSERT_TRUE(good.T_CT.has_value());
  EXPECT_LT((good.T_CT->matrix() - T_CT_.matrix()).cwiseAbs().maxCoeff(), 1e-6);
  std::vector<LedCorrespondence> swapped{{0, 1}, {1, 0}, {2, 2}, {3, 3}, {4, 4}};
  EXPECT_FALSE(search.Verify(swapped, detections, camera_).verified);
  // Occluded LED: four true correspondences still verify; three cannot be verified.
  EXPECT_TRUE(search.Verify({{0, 0}, {1, 1}, {3, 3}, {4, 4}}, detections, camera_).verified);
  EXPECT_FALSE(search.Verify({{0, 0}, {1, 1}, {3, 3}}, detections, camera_).verified);
}

TEST_P(LedCorrespondenceSearchTest, TooFewDetectionsGiveNoCorrespondences) {
  LedCorrespondenceSearch search(configuration_.p_T(), Params());
  const LedCorrespondenceResult result = search.FindByBruteForce(Detect({0, 1}), camera_);
  EXPECT_TRUE(result.correspondences.empty());
  EXPECT_FALSE(result.T_CT.has_value());
}

INSTANTIATE_TEST_SUITE_P(KneipAndAp3p, LedCorrespondenceSearchTest,
                         ::testing::Values(P3pMethod::kKneip, P3pMethod::kAp3p),
                         [](const auto& info) { return P3pMethodName(info.param); });

}  // namespace
}  // namespace aperture::perception
