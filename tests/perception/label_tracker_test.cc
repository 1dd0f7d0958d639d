// Label tracking (seed 002 Alg. 1): the FOE/divergence fit on noisy synthetic tracks of a known
// zoom, propagation of F, B, x_s and C through a synthetic zoom sequence, the safe-point Kalman
// filter, and the input checks.
#include "perception/ts2p/label_tracker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "perception/ts2p/safe_point_filter.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

// Tracks of a zoom x -> x + alpha (x - foe) with Gaussian pixel noise, points uniform in the
// 576 x 384 image.
void ZoomTracks(const Eigen::Vector2d& foe, double alpha, double sigma_px, int count,
                std::mt19937* rng, std::vector<Eigen::Vector2d>* before,
                std::vector<Eigen::Vector2d>* after) {
  std::uniform_real_distribution<double> u(0.0, 576.0), v(0.0, 384.0);
  std::normal_distribution<double> noise(0.0, sigma_px);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d p(u(*rng), v(*rng));
    before->push_back(p);
    after->push_back(p + alpha * (p - foe) + Eigen::Vector2d(noise(*rng), noise(*rng)));
  }
}

// The FOE is x_0 = -c / alpha: its error is ~ sigma / (alpha sqrt(n)) per axis (the offset's
// error sigma / sqrt(n), magnified by 1 / alpha). With KLT's ~0.1 px on textured corners, the 150
// corners of a set and a 5 % expansion (three frames at the paper's approach), that is 0.13 px.
constexpr double kKltSigmaPx = 0.1;
constexpr double kExpansion = 0.05;
constexpr int kTracks = 150;

TEST(FitExpansionTest, RecoversFoeAndDivergenceFromNoisyZoomTracks) {
  std::mt19937 rng(3);
  for (const Eigen::Vector2d& foe : {Eigen::Vector2d(288, 192), Eigen::Vector2d(150.5, 260.25)}) {
    std::vector<Eigen::Vector2d> before, after;
    ZoomTracks(foe, kExpansion, kKltSigmaPx, kTracks, &rng, &before, &after);
    const ExpansionFit fit = FitExpansion(before, after, 1e-5);
    ASSERT_TRUE(fit.ok);
    EXPECT_NEAR(fit.alpha, kExpansion, 1e-4);
    EXPECT_LT((fit.foe_px - foe).norm(), 0.5) << fit.foe_px.transpose();
  }
}

TEST(FitExpansionTest, FoeErrorFollowsTheNoiseModel) {
  // 200 draws at 0.5 px noise, 40 tracks (k_F), 1.5 % expansion: RMS error per axis near
  // sigma / (alpha sqrt(n)) times the spread factor sqrt(1 + x0^2 / var(x)) of a line fit's
  // intercept; a wrong fit (e.g. y from x's divergence only) is off by far more than 1.5x.
  std::mt19937 rng(8);
  const Eigen::Vector2d foe(288, 192);
  const double sigma = 0.5, alpha = 0.015;
  const int n = 40;
  double sum_squared = 0.0;
  const int draws = 200;
  for (int i = 0; i < draws; ++i) {
    std::vector<Eigen::Vector2d> before, after;
    ZoomTracks(foe, alpha, sigma, n, &rng, &before, &after);
    const ExpansionFit fit = FitExpansion(before, after, 1e-5);
    ASSERT_TRUE(fit.ok);
    sum_squared += (fit.foe_px - foe).squaredNorm() / 2.0;
  }
  // Uniform points: var(x) = 576^2 / 12, var(y) = 384^2 / 12; x_0 at the centre of the spread.
  const double predicted = sigma / (alpha * std::sqrt(n));
  const double rms = std::sqrt(sum_squared / draws);
  EXPECT_GT(rms, predicted / 1.5);
  EXPECT_LT(rms, predicted * 1.5);
}

TEST(FitExpansionTest, RejectsTracksOnTheOtherDepth) {
  std::mt19937 rng(5);
  const Eigen::Vector2d foe(300, 170);
  std::vector<Eigen::Vector2d> before, after;
  ZoomTracks(foe, kExpansion, kKltSigmaPx, 120, &rng, &before, &after);
  // 30 corners from the far wall: a fifth of the expansion (Z_B ~ 5 Z_F away).
  std::vector<Eigen::Vector2d> far_before, far_after;
  ZoomTracks(foe, kExpansion / 5, kKltSigmaPx, 30, &rng, &far_before, &far_after);
  before.insert(before.end(), far_before.begin(), far_before.end());
  after.insert(after.end(), far_after.begin(), far_after.end());
  const ExpansionFit fit = FitExpansion(before, after, 1e-5);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.alpha, kExpansion, 5e-4);
  EXPECT_LT((fit.foe_px - foe).norm(), 0.5);
  EXPECT_LE(fit.inliers, 125);  // the far-wall tracks are gated out
}

TEST(FitExpansionTest, PureTranslationHasNoFoeButPropagates) {
  const std::vector<Eigen::Vector2d> before{{10, 10}, {100, 20}, {50, 200}, {300, 300}};
  std::vector<Eigen::Vector2d> after;
  for (const auto& p : before) after.push_back(p + Eigen::Vector2d(2.0, -1.0));
  const ExpansionFit fit = FitExpansion(before, after, 1e-5);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.alpha, 0.0, 1e-9);
  EXPECT_TRUE(std::isnan(fit.foe_px.x()));
  EXPECT_LT((fit.Apply({7, 8}) - Eigen::Vector2d(9, 7)).norm(), 1e-9);
  EXPECT_FALSE(FitExpansion({{1, 1}, {2, 2}}, {{1, 1}, {2, 2}}, 1e-5).ok);  // too few tracks
}

// Smooth random texture, zoomed by `scale` about `foe` (exact affine resampling).
cv::Mat Zoomed(const cv::Mat& texture, double scale, const Eigen::Vector2d& foe) {
  cv::Mat out;
  const cv::Matx23d warp(scale, 0, (1 - scale) * foe.x(), 0, scale, (1 - scale) * foe.y());
  cv::warpAffine(texture, out, warp, texture.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return out;
}

// A 576 x 384 blurred-noise texture: corners everywhere, KLT's ~0.1 px.
cv::Mat NoiseTexture(std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat noise(384, 576, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat texture;
  noise.convertTo(texture, CV_8U);
  return texture;
}

TEST(LabelTrackerTest, PropagationMatchesASyntheticZoom) {
  const cv::Mat texture = NoiseTexture(9);
  // An opening: ellipse around (270, 200); the zoom's FOE off its centre.
  cv::Mat opening = cv::Mat::zeros(texture.size(), CV_8U);
  cv::ellipse(opening, cv::Point(270, 200), cv::Size(90, 60), 0, 0, 360, 255, -1);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(opening.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  const Eigen::Vector2d foe(300, 180), x_s(270, 200);

  LabelTracker tracker(LabelTrackerParams{});
  tracker.Initialize(texture, opening, x_s, contours[0], 0.0, 0);
  const double step = 1.01;  // per frame
  double scale = 1.0;
  OpeningTrack track;
  for (int frame = 1; frame <= 15; ++frame) {
    scale *= step;
    track = tracker.Track(Zoomed(texture, scale, foe), frame / 30.0, frame);
    ASSERT_TRUE(track.valid) << "frame " << frame;
    EXPECT_NEAR(track.divergence, step - 1.0, 1.5e-3) << "frame " << frame;
    EXPECT_LT((track.foe_px - foe).norm(), 3.0) << "frame " << frame;
  }
  // After 15 frames (16 % zoom) x_s, the contour and both sets follow the zoom to ~1 px.
  const Eigen::Vector2d x_s_true = foe + scale * (x_s - foe);
  EXPECT_LT((track.safe_point_measured_px - x_s_true).norm(), 1.0);
  const cv::Point& c0 = contours[0][0];
  const Eigen::Vector2d c0_true = foe + scale * (Eigen::Vector2d(c0.x, c0.y) - foe);
  const std::size_t n = track.contour_px.size();
  ASSERT_EQ(n, contours[0].size());
  EXPECT_LT((track.contour_px[0] - c0_true).norm(), 1.5);
  cv::Mat opening_true;
  const cv::Matx23d warp(scale, 0, (1 - scale) * foe.x(), 0, scale, (1 - scale) * foe.y());
  cv::warpAffine(opening, opening_true, warp, opening.size(), cv::INTER_NEAREST);
  cv::Mat background_true;
  cv::erode(opening_true, background_true,
            cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(17, 17)));  // eps3 8 px * s
  const cv::Mat b = tracker.BackgroundMask();
  const double overlap = cv::countNonZero(b & background_true);
  const double union_area = cv::countNonZero(b | background_true);
  EXPECT_GT(overlap / union_area, 0.95);
  // F stays outside the opening.
  EXPECT_EQ(cv::countNonZero(tracker.ForegroundMask() & opening_true), 0);
}

// Two depths: the wall expands faster than the background seen through a large opening, whose
// B set outgrows the F ring in the image (so x_s comes from B). The contour is the wall's rim: it
// must follow the wall's zoom, not the background's.
TEST(LabelTrackerTest, ContourFollowsTheWallWhenTheBackgroundSetIsLarger) {
  const cv::Mat wall = NoiseTexture(11), background = NoiseTexture(12);
  cv::Mat opening = cv::Mat::zeros(wall.size(), CV_8U);
  cv::ellipse(opening, cv::Point(288, 192), cv::Size(150, 110), 0, 0, 360, 255, -1);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(opening.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const Eigen::Vector2d foe(300, 180);
  auto frame = [&](double wall_scale, double background_scale) {
    cv::Mat out = Zoomed(background, background_scale, foe);
    cv::Mat opening_now;
    const cv::Matx23d warp(wall_scale, 0, (1 - wall_scale) * foe.x(), 0, wall_scale,
                           (1 - wall_scale) * foe.y());
    cv::warpAffine(opening, opening_now, warp, opening.size(), cv::INTER_NEAREST);
    Zoomed(wall, wall_scale, foe).copyTo(out, ~opening_now);
    return out;
  };

  LabelTracker tracker(LabelTrackerParams{});
  tracker.Initialize(frame(1.0, 1.0), opening, Eigen::Vector2d(288, 192), contours[0], 0.0, 0);
  const double wall_step = 1.01, background_step = 1.003;  // per frame
  double wall_scale = 1.0, background_scale = 1.0;
  OpeningTrack track;
  for (int k = 1; k <= 15; ++k) {
    wall_scale *= wall_step;
    background_scale *= background_step;
    track = tracker.Track(frame(wall_scale, background_scale), k / 30.0, k);
    ASSERT_TRUE(track.valid) << "frame " << k;
  }
  EXPECT_EQ(track.safe_point_source, 'B');
  // The background's zoom would leave the rim ~17 px inside the true one.
  ASSERT_EQ(track.contour_px.size(), contours[0].size());
  double worst_px = 0.0;
  for (std::size_t i = 0; i < contours[0].size(); ++i) {
    const Eigen::Vector2d c(contours[0][i].x, contours[0][i].y);
    worst_px = std::max(worst_px, (track.contour_px[i] - (foe + wall_scale * (c - foe))).norm());
  }
  EXPECT_LT(worst_px, 2.0);
}

TEST(SafePointFilterTest, SmoothsNoisyConstantVelocityMotion) {
  SafePointFilter filter(SafePointFilterParams{});
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 4.0);
  double raw_error = 0.0, filtered_error = 0.0;
  int count = 0;
  for (int i = 0; i <= 90; ++i) {
    const double t = i / 30.0;
    const Eigen::Vector2d truth(200.0 + 30.0 * t, 150.0 - 12.0 * t);
    const Eigen::Vector2d measured = truth + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d filtered = filter.Update(measured, t);
    if (i >= 30) {  // after the velocity has converged
      raw_error += (measured - truth).norm();
      filtered_error += (filtered - truth).norm();
      ++count;
    }
  }
  EXPECT_LT(filtered_error, 0.6 * raw_error);
  EXPECT_NEAR(filter.velocity_px_per_s().x(), 30.0, 8.0);
  EXPECT_NE(test_support::MessageOf([&] {
              filter.Update({0, 0}, 1.0);
            }).find("before"),
            std::string::npos);
}

TEST(LabelTrackerTest, RejectsBadInput) {
  LabelTrackerParams params;
  params.foreground_outer_radius_px = 5.0;  // inside eps2
  EXPECT_NE(test_support::MessageOf([&] { LabelTracker t(params); }).find("foreground_outer"),
            std::string::npos);
  LabelTracker tracker(LabelTrackerParams{});
  const cv::Mat gray(100, 100, CV_8U, cv::Scalar(0));
  EXPECT_NE(test_support::MessageOf([&] {
              tracker.Initialize(gray, cv::Mat::zeros(100, 100, CV_8U), {50, 50}, {}, 0.0, 0);
            }).find("non-empty"),
            std::string::npos);
  EXPECT_FALSE(tracker.Track(gray, 0.0, 0).valid);  // not initialized: no track
}

}  // namespace
}  // namespace aperture::perception
