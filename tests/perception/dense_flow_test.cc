// Every DenseFlow method against the known flow of a synthetic textured image that is translated
// or zoomed (exact warps of a smooth random texture), plus the input checks.
#include "perception/flow/dense_flow.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <opencv2/imgproc.hpp>

#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

// Band-limited random texture (8-bit), so every method's pyramid sees structure at each level.
cv::Mat Texture(int width, int height, int seed) {
  cv::RNG rng(seed);
  cv::Mat noise(height, width, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(0, 0), 2.0);
  cv::Mat image;
  cv::normalize(smooth, smooth, 20, 235, cv::NORM_MINMAX);
  smooth.convertTo(image, CV_8U);
  return image;
}

// `to` = `from` moved by x -> A x + b, so the true flow at x is (A - I) x + b.
struct Motion {
  cv::Matx23d affine;
  Eigen::Vector2d FlowAt(double x, double y) const {
    return {affine(0, 0) * x + affine(0, 1) * y + affine(0, 2) - x,
            affine(1, 0) * x + affine(1, 1) * y + affine(1, 2) - y};
  }
};

Motion Translation(double dx, double dy) { return {cv::Matx23d(1, 0, dx, 0, 1, dy)}; }
Motion Zoom(double scale, double cx, double cy) {
  return {cv::Matx23d(scale, 0, (1 - scale) * cx, 0, scale, (1 - scale) * cy)};
}

// Mean end-point error [px] over the image without a border (the warp leaves the edges empty and
// every method extrapolates there).
double MeanEndpointError(const cv::Mat& flow, const Motion& motion, int border) {
  double sum = 0.0;
  int count = 0;
  for (int y = border; y < flow.rows - border; ++y) {
    for (int x = border; x < flow.cols - border; ++x) {
      const cv::Vec2f f = flow.at<cv::Vec2f>(y, x);
      sum += (Eigen::Vector2d(f[0], f[1]) - motion.FlowAt(x, y)).norm();
      ++count;
    }
  }
  return sum / count;
}

double EndpointErrorOf(const std::string& method, bool refine, const Motion& motion) {
  const cv::Mat from = Texture(128, 96, 7);
  cv::Mat to;
  // warpAffine with WARP_INVERSE_MAP off maps from -> to by `affine`.
  cv::warpAffine(from, to, cv::Mat(motion.affine), from.size(), cv::INTER_CUBIC,
                 cv::BORDER_REFLECT);
  DenseFlowParams params;
  params.method = method;
  params.variational_refinement = refine;
  DenseFlow flow(params);
  const cv::Mat result = flow.Compute(from, to);
  EXPECT_EQ(result.type(), CV_32FC2);
  EXPECT_EQ(result.size(), from.size());
  return MeanEndpointError(result, motion, 16);
}

class DenseFlowMethodTest : public ::testing::TestWithParam<std::string> {};

// 0.3 px: a tenth of the largest displacement, above the ~0.1 px that cubic resampling and the
// methods' smoothness leave on this texture, below what a wrong sign, scale or axis gives (>= 2
// px).
constexpr double kToleranceEpePx = 0.3;

TEST_P(DenseFlowMethodTest, RecoversSubpixelTranslation) {
  EXPECT_LT(EndpointErrorOf(GetParam(), false, Translation(2.6, -1.4)), kToleranceEpePx);
}

TEST_P(DenseFlowMethodTest, RecoversZoomAboutAnOffCentrePoint) {
  // 3 % zoom: flows from 0 px at (60, 50) to ~2 px at the corners, like an approach.
  EXPECT_LT(EndpointErrorOf(GetParam(), false, Zoom(1.03, 60, 50)), kToleranceEpePx);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, DenseFlowMethodTest,
                         ::testing::ValuesIn(DenseFlowMethodNames()),
                         [](const auto& info) { return info.param; });

TEST(DenseFlowTest, VariationalRefinementKeepsAnAccurateFlowAccurate) {
  EXPECT_LT(EndpointErrorOf("dis_fast", true, Zoom(1.03, 60, 50)), kToleranceEpePx);
  DenseFlowParams params;
  params.variational_refinement = true;
  EXPECT_EQ(DenseFlow(params).Describe(), "dis_medium+variational");
}

// TS²P's default: DIS-medium without its own variational refinement stays sub-pixel accurate on
// a textured zoom; the setting shows in the name and a bad count names the field.
TEST(DenseFlowTest, DisRefinementIterationsOverrideThePreset) {
  DenseFlowParams params;
  params.dis_refinement_iterations = 0;
  DenseFlow flow(params);
  EXPECT_EQ(flow.Describe(), "dis_medium/refine0");
  const Motion zoom = Zoom(1.03, 60, 50);
  const cv::Mat from = Texture(128, 96, 1);
  cv::Mat to;
  cv::warpAffine(from, to, cv::Mat(zoom.affine), from.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  EXPECT_LT(MeanEndpointError(flow.Compute(from, to), zoom, 16), kToleranceEpePx);
  params.dis_refinement_iterations = -2;
  EXPECT_NE(
      test_support::MessageOf([&] { DenseFlow bad(params); }).find("dis_refinement_iterations"),
      std::string::npos);
}

TEST(DenseFlowTest, RejectsUnknownMethodsAndBadImages) {
  DenseFlowParams params;
  params.method = "flownet2";
  const std::string unknown = test_support::MessageOf([&] { DenseFlow flow(params); });
  EXPECT_NE(unknown.find("flownet2"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("dis_medium"), std::string::npos) << unknown;

  DenseFlow flow(DenseFlowParams{});
  const cv::Mat a = Texture(64, 48, 1);
  const std::string size = test_support::MessageOf([&] { flow.Compute(a, Texture(32, 48, 1)); });
  EXPECT_NE(size.find("32x48"), std::string::npos) << size;
  cv::Mat floating;
  a.convertTo(floating, CV_32F);
  EXPECT_NE(test_support::MessageOf([&] { flow.Compute(floating, floating); }).find("8-bit"),
            std::string::npos);
}

TEST(DenseFlowTest, AcceptsBgrFrames) {
  cv::Mat from = Texture(96, 64, 3), to, from_bgr, to_bgr;
  cv::warpAffine(from, to, cv::Mat(Translation(1.5, 0.5).affine), from.size(), cv::INTER_CUBIC,
                 cv::BORDER_REFLECT);
  cv::cvtColor(from, from_bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(to, to_bgr, cv::COLOR_GRAY2BGR);
  DenseFlow flow(DenseFlowParams{});
  EXPECT_LT(MeanEndpointError(flow.Compute(from_bgr, to_bgr), Translation(1.5, 0.5), 16),
            kToleranceEpePx);
}

}  // namespace
}  // namespace aperture::perception
