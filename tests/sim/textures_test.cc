#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "sim/scene/textures.h"

namespace aperture::sim {
namespace {

// Texel arithmetic is float; 1e-5 covers float rounding of values in [0, 1].
constexpr float kTol = 1e-5f;

bool Equal(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(TexturesTest, CheckerboardSquaresAndBorder) {
  const Rgb dark(0.1f, 0.2f, 0.3f), light(0.9f, 0.8f, 0.7f), border(0.5f, 0.5f, 0.5f);
  const Texture t = Texture::Checkerboard(0.04, 5, 4, 0.02, dark, light, border);
  EXPECT_TRUE(t.Sample(0.02 + 0.5 * 0.04, 0.02 + 0.5 * 0.04).isApprox(dark));
  EXPECT_TRUE(t.Sample(0.02 + 1.5 * 0.04, 0.02 + 0.5 * 0.04).isApprox(light));
  EXPECT_TRUE(t.Sample(0.02 + 1.5 * 0.04, 0.02 + 1.5 * 0.04).isApprox(dark));
  EXPECT_TRUE(t.Sample(0.02 + 4.5 * 0.04, 0.02 + 3.5 * 0.04).isApprox(light));
  EXPECT_TRUE(t.Sample(0.01, 0.1).isApprox(border));                 // left margin
  EXPECT_TRUE(t.Sample(0.02 + 5.01 * 0.04, 0.1).isApprox(border));   // right of the board
  const Texture infinite = Texture::Checkerboard(1.0);
  EXPECT_TRUE(infinite.Sample(-0.5, -0.5).isApprox(infinite.Sample(0.5, 0.5)));
  EXPECT_FALSE(infinite.Sample(-0.5, 0.5).isApprox(infinite.Sample(0.5, 0.5)));
  EXPECT_THROW(Texture::Checkerboard(0.0), std::invalid_argument);
}

TEST(TexturesTest, BilinearSamplingInterpolatesTexelCentresAndRepeats) {
  cv::Mat image(2, 2, CV_32FC3);
  image.at<cv::Vec3f>(0, 0) = {0.0f, 0.0f, 0.0f};
  image.at<cv::Vec3f>(0, 1) = {1.0f, 0.5f, 0.0f};
  image.at<cv::Vec3f>(1, 0) = {0.0f, 1.0f, 0.0f};
  image.at<cv::Vec3f>(1, 1) = {1.0f, 1.0f, 1.0f};
  const double s = 0.1;  // texel size [m]: texel (c, r) centre at ((c + 0.5) s, (r + 0.5) s)
  const Texture t(image, s);
  EXPECT_TRUE(t.Sample(1.5 * s, 0.5 * s).isApprox(Rgb(1.0f, 0.5f, 0.0f), kTol));
  EXPECT_TRUE(t.Sample(1.0 * s, 0.5 * s).isApprox(Rgb(0.5f, 0.25f, 0.0f), kTol));
  EXPECT_TRUE(t.Sample(1.0 * s, 1.0 * s).isApprox(Rgb(0.5f, 0.625f, 0.25f), kTol));
  // Period 2 texels: sampling one period further gives the same value; across the wrap edge
  // (u = 0) the value interpolates texel column 1 and column 0.
  EXPECT_TRUE(t.Sample(1.3 * s + 2 * s, 0.7 * s).isApprox(t.Sample(1.3 * s, 0.7 * s), kTol));
  EXPECT_TRUE(t.Sample(0.0, 0.5 * s).isApprox(Rgb(0.5f, 0.25f, 0.0f), kTol));
  const Texture nearest(image, s, Texture::Filter::kNearest, Texture::Wrap::kClamp);
  EXPECT_TRUE(nearest.Sample(1.05 * s, 0.3 * s).isApprox(Rgb(1.0f, 0.5f, 0.0f), kTol));
  EXPECT_TRUE(nearest.Sample(-5.0 * s, 0.3 * s).isApprox(Rgb(0.0f, 0.0f, 0.0f), kTol));
  EXPECT_THROW(Texture(cv::Mat(), s), std::invalid_argument);
  EXPECT_THROW(Texture(image, 0.0), std::invalid_argument);
}

TEST(TexturesTest, LargeFootprintsReadTheAveragedMipLevel) {
  // Alternating black / white texels (1 cm): a sample covering 8 cm must see their mean, 0.5,
  // instead of aliasing to 0 or 1; a point sample at a texel centre sees the texel.
  cv::Mat image(64, 64, CV_32FC3);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) image.at<cv::Vec3f>(y, x) = cv::Vec3f::all(static_cast<float>((x + y) % 2));
  }
  const Texture t(image, 0.01);
  EXPECT_NEAR(t.Sample(0.005, 0.005, 0.0).x(), 0.0f, kTol);
  EXPECT_NEAR(t.Sample(0.015, 0.005, 0.0).x(), 1.0f, kTol);
  for (const double u : {0.005, 0.013, 0.2371}) EXPECT_NEAR(t.Sample(u, 0.31, 0.08).x(), 0.5f, kTol);
}

TEST(TexturesTest, GrayImagesSampleLikeTheirColourTwin) {
  // A gray image (R = G = B) is stored with one channel; its samples must equal those of the
  // same texels in a colour image (stored RGB; blue differs, red and green are the gray texels)
  // at every mip level and for both filters.
  cv::Mat gray(32, 32, CV_32FC3), colour;
  cv::randu(gray, 0.0, 1.0);
  cv::Mat channels[3];
  cv::split(gray, channels);
  channels[1] = channels[0].clone();
  channels[2] = channels[0].clone();
  cv::merge(channels, 3, gray);
  channels[2] = 1.0f - channels[0];
  cv::merge(channels, 3, colour);
  for (const Texture::Filter filter : {Texture::Filter::kBilinear, Texture::Filter::kNearest}) {
    const Texture g(gray, 0.01, filter), c(colour, 0.01, filter);
    for (const double footprint : {0.0, 0.021, 0.05, 0.2}) {
      for (double u = -0.1; u < 0.4; u += 0.0137) {
        const double v = 0.31 - 0.7 * u;
        const Rgb a = g.Sample(u, v, footprint), b = c.Sample(u, v, footprint);
        EXPECT_NEAR(a.x(), b.x(), kTol) << u << " " << footprint;
        EXPECT_NEAR(a.y(), b.y(), kTol);
        EXPECT_EQ(a.z(), a.x());
      }
    }
  }
}

using Generator = std::shared_ptr<const Texture> (*)(const ProceduralTextureParams&);

std::shared_ptr<const Texture> Noise(const ProceduralTextureParams& p) { return MakeValueNoiseTexture(p); }
std::shared_ptr<const Texture> Newspaper(const ProceduralTextureParams& p) { return MakeNewspaperTexture(p); }

class ProceduralTextureTest : public ::testing::TestWithParam<Generator> {};

TEST_P(ProceduralTextureTest, SameSeedSameTexelsOtherSeedOtherTexels) {
  ProceduralTextureParams params;
  params.size_px = 128;
  params.seed = 7;
  const auto a = GetParam()(params);
  const auto b = GetParam()(params);
  params.seed = 8;
  const auto c = GetParam()(params);
  EXPECT_TRUE(Equal(a->image(), b->image()));
  EXPECT_FALSE(Equal(a->image(), c->image()));
  EXPECT_EQ(a->image().rows, 128);
  // Not flat: a texture with no contrast would be useless for vision front ends.
  cv::Scalar mean, stddev;
  cv::meanStdDev(a->image().reshape(1), mean, stddev);
  EXPECT_GT(stddev[0], 0.05);
  double lo, hi;
  cv::minMaxLoc(a->image().reshape(1), &lo, &hi);
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
}

INSTANTIATE_TEST_SUITE_P(Generators, ProceduralTextureTest,
                         ::testing::Values(&Noise, &Newspaper, &MakeBarkTexture, &MakeGrassTexture));

TEST(TexturesTest, ValueNoiseTilesSeamlessly) {
  ProceduralTextureParams params;
  params.size_px = 128;
  const auto t = MakeValueNoiseTexture(params, 4, 32);
  const cv::Mat& im = t->image();
  // Across the wrap edge (last column -> first) the step is as small as between neighbours.
  double wrap_step = 0.0, inner_step = 0.0;
  for (int y = 0; y < im.rows; ++y) {
    wrap_step += std::abs(im.at<cv::Vec3f>(y, im.cols - 1)[0] - im.at<cv::Vec3f>(y, 0)[0]);
    inner_step += std::abs(im.at<cv::Vec3f>(y, 60)[0] - im.at<cv::Vec3f>(y, 61)[0]);
  }
  EXPECT_LT(wrap_step, 3.0 * inner_step + 1e-3);
}

TEST(TexturesTest, NewspaperHasDarkTextOnLightPaper) {
  ProceduralTextureParams params;
  params.size_px = 256;
  const auto texture = MakeNewspaperTexture(params, 3);
  const cv::Mat& im = texture->image();
  int dark = 0;
  for (int y = 0; y < im.rows; ++y) {
    for (int x = 0; x < im.cols; ++x) dark += im.at<cv::Vec3f>(y, x)[0] < 0.5f;
  }
  const double fraction = static_cast<double>(dark) / im.total();
  EXPECT_GT(fraction, 0.03);  // columns of words
  EXPECT_LT(fraction, 0.5);   // still mostly paper
}

TEST(TexturesTest, GrassIsGreenAndBarkIsBrown) {
  ProceduralTextureParams params;
  params.size_px = 64;
  const cv::Scalar grass = cv::mean(MakeGrassTexture(params)->image());  // RGB
  EXPECT_GT(grass[1], grass[0]);
  EXPECT_GT(grass[1], grass[2]);
  const cv::Scalar bark = cv::mean(MakeBarkTexture(params)->image());
  EXPECT_GT(bark[0], bark[1]);
  EXPECT_GT(bark[1], bark[2]);
}

}  // namespace
}  // namespace aperture::sim
