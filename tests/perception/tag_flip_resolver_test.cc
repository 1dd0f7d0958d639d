#include "perception/tags/tag_flip_resolver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "perception/camera/pinhole_camera.h"
#include "control/so3.h"

namespace aperture::perception {
namespace {

Eigen::Isometry3d Rotated(const Eigen::Vector3d& phi, double z_m = 2.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = control::ExpSo3(phi);
  T.translation() = Eigen::Vector3d(0, 0, z_m);
  return T;
}

// A tag whose candidates tilt about x_C, best = the first; the alternative's RMS error is 1 px,
// the best's sqrt(ratio) px (ambiguity_ratio = best^2 / alternative^2).
TagPoseInImage Ambiguous(int id, double best_tilt, double alternative_tilt, double ratio) {
  TagPoseInImage tag{"tag36h11", id, {}};
  tag.pose.best.T_CT = Rotated({best_tilt, 0, 0});
  tag.pose.best.rms_px = std::sqrt(ratio);
  tag.pose.alternative =
      TagPoseCandidate{Rotated({alternative_tilt, 0, 0}), Matrix6d::Identity(), 1.0};
  tag.pose.ambiguity_ratio = ratio;
  return tag;
}

TEST(TagFlipResolver, TrustsTheImageWhenItDecides) {
  TagFlipResolver resolver;
  const std::vector<FlipChoice> choices = resolver.Resolve(0.0, {Ambiguous(1, 0.3, -0.3, 0.05)});
  EXPECT_FALSE(choices[0].use_alternative);
  EXPECT_EQ(choices[0].decision, FlipDecision::kUnambiguous);
}

TEST(TagFlipResolver, AmbiguousTagFollowsACoplanarDecidedTag) {
  TagFlipResolver resolver;
  // Tag 1 (decided) lies at +0.2 rad; tag 2's alternative (+0.2) matches it, its best (-0.2)
  // does not (23 deg > 15 deg).
  const std::vector<FlipChoice> choices =
      resolver.Resolve(0.0, {Ambiguous(1, 0.2, -0.25, 0.01), Ambiguous(2, -0.2, 0.2, 0.9)});
  EXPECT_TRUE(choices[1].use_alternative);
  EXPECT_EQ(choices[1].decision, FlipDecision::kCoplanar);
}

TEST(TagFlipResolver, AmbiguousTagKeepsItsHistoryWithinTheGap) {
  TagFlipResolver resolver;
  resolver.Resolve(0.0, {Ambiguous(4, 0.35, -0.35, 0.02)});  // decided: +0.35
  // Next frame the image cannot tell: best is the mirror; the summed errors pick +0.33.
  std::vector<FlipChoice> choices = resolver.Resolve(0.1, {Ambiguous(4, -0.33, 0.33, 0.95)});
  EXPECT_TRUE(choices[0].use_alternative);
  EXPECT_EQ(choices[0].decision, FlipDecision::kTemporal);
  // After a gap longer than max_track_gap_s there is no history: lowest error.
  choices = resolver.Resolve(5.0, {Ambiguous(4, -0.33, 0.33, 0.95)});
  EXPECT_FALSE(choices[0].use_alternative);
  EXPECT_EQ(choices[0].decision, FlipDecision::kLowestError);
}

TEST(TagFlipResolver, ErrorsWithinTheCornerNoiseDoNotDecide) {
  // A small tag: ratio 0.1 as above, but both errors tiny (0.03 and 0.1 px RMS): the alternative
  // is worse by 4 (0.1^2 - 0.03^2) = 0.036 px^2 < min_error_gap_px2, so the image does not
  // decide; the tag follows the large tag decided in the same image (+0.3 rad, its alternative).
  TagPoseInImage small = Ambiguous(6, -0.3, 0.3, 0.1);
  small.pose.best.rms_px *= 0.1;
  small.pose.alternative->rms_px *= 0.1;
  const TagPoseInImage large = Ambiguous(1, 0.3, -0.3, 0.1);
  const TagFlipResolverParams params;
  EXPECT_FALSE(ImageDecides(small.pose, params));
  EXPECT_TRUE(ImageDecides(large.pose, params));  // 4 (1 - 0.1) = 3.6 px^2
  TagFlipResolver resolver(params);
  const std::vector<FlipChoice> choices = resolver.Resolve(0.0, {large, small});
  EXPECT_EQ(choices[0].decision, FlipDecision::kUnambiguous);
  EXPECT_TRUE(choices[1].use_alternative);
  EXPECT_EQ(choices[1].decision, FlipDecision::kCoplanar);
}

TEST(TagFlipResolver, DisabledAlwaysTakesTheLowestError) {
  TagFlipResolverParams params;
  params.enabled = false;
  TagFlipResolver resolver(params);
  const std::vector<FlipChoice> choices =
      resolver.Resolve(0.0, {Ambiguous(1, 0.2, -0.25, 0.01), Ambiguous(2, -0.2, 0.2, 0.9)});
  EXPECT_FALSE(choices[0].use_alternative);
  EXPECT_FALSE(choices[1].use_alternative);
}

TEST(TagFlipResolver, RejectsBadParams) {
  TagFlipResolverParams params;
  params.max_ambiguity_ratio = 1.5;
  EXPECT_THROW(TagFlipResolver{params}, std::invalid_argument);
  params = {};
  params.min_error_gap_px2 = -0.1;
  EXPECT_THROW(TagFlipResolver{params}, std::invalid_argument);
}

// End to end on synthetic corners: a downward camera drifting over six flat 0.25 m tags at
// 2.5 m (90 deg field of view, 0.4 px corner noise). A flip: the chosen candidate is the one
// farther from the truth while the two differ by more than 10 deg (closer pairs are noise, not
// a flip). The resolver flips at most half as often as the lowest reprojection error.
TEST(TagFlipResolver, LowersTheFlipRateOnANoisySequence) {
  const PinholeCamera camera(640, 480, {320.0, 320.0, 319.5, 239.5});
  std::vector<Eigen::Isometry3d> T_WT;
  for (int k = 0; k < 6; ++k) T_WT.push_back(Rotated({M_PI, 0, 0.5 * k}, 0.0));
  for (int k = 0; k < 6; ++k)
    T_WT[k].translation() = Eigen::Vector3d(0.8 * (k % 3) - 0.8, 0.9 * (k / 3) - 0.45, 0.0);
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.4);
  auto flip_rate = [&](bool enabled) {
    TagFlipResolverParams params;
    params.enabled = enabled;
    TagFlipResolver resolver(params);
    int flips = 0, total = 0;
    for (int frame = 0; frame < 150; ++frame) {
      Eigen::Isometry3d T_WC = Rotated({M_PI, 0, 0.01 * frame}, 2.5);
      T_WC.translation().x() = -0.5 + 0.007 * frame;
      std::vector<TagPoseInImage> tags;
      std::vector<Eigen::Isometry3d> truth;
      for (int k = 0; k < 6; ++k) {
        const Eigen::Isometry3d T_CT = T_WC.inverse() * T_WT[k];
        std::array<Eigen::Vector2d, 4> corners;
        bool visible = true;
        for (int c = 0; c < 4; ++c) {
          visible = visible && camera.Project(T_CT * TagCorner(c, 0.25), &corners[c]) &&
                    camera.IsInImage(corners[c]);
          corners[c] += Eigen::Vector2d(noise(rng), noise(rng));
        }
        if (!visible) continue;
        const std::optional<TagPose> pose = EstimateTagPose(camera, corners, 0.25);
        if (!pose) continue;
        tags.push_back({"tag36h11", k, *pose});
        truth.push_back(T_CT);
      }
      const std::vector<FlipChoice> choices = resolver.Resolve(frame / 30.0, tags);
      for (std::size_t i = 0; i < tags.size(); ++i) {
        const TagPoseCandidate& chosen =
            choices[i].use_alternative ? *tags[i].pose.alternative : tags[i].pose.best;
        if (!tags[i].pose.alternative) continue;
        const TagPoseCandidate& other =
            choices[i].use_alternative ? tags[i].pose.best : *tags[i].pose.alternative;
        auto angle_deg = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
          return control::LogSo3(a.linear().transpose() * b.linear()).norm() * 180 / M_PI;
        };
        if (angle_deg(chosen.T_CT, other.T_CT) <= 10.0) continue;
        flips += angle_deg(chosen.T_CT, truth[i]) > angle_deg(other.T_CT, truth[i]);
        ++total;
      }
    }
    EXPECT_GT(total, 200);
    return double(flips) / total;
  };
  const double without = flip_rate(false);
  const double with = flip_rate(true);
  std::cout << "flip rate: lowest error " << without << ", resolver " << with << "\n";
  EXPECT_GT(without, 0.05) << "the sequence should be ambiguous enough to need resolving";
  EXPECT_LT(with, 0.5 * without);
}

}  // namespace
}  // namespace aperture::perception
