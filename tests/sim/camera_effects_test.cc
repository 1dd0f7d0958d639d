#include "sim/render/camera_effects.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <opencv2/core.hpp>

#include "render_test_util.h"

namespace aperture::sim {
namespace {

using testing::Pose;

cv::Mat Uniform(float value) { return cv::Mat(240, 320, CV_32FC1, cv::Scalar(value)); }

TEST(CameraEffectsTest, NoiseIsSeededPerFrameAndThreadIndependent) {
  CameraEffectsParams params;
  params.read_noise_sigma = 0.02;
  params.full_well_electrons = 2000.0;
  params.seed = 11;
  const CameraEffects effects(params);
  const cv::Mat a = effects.ToImage8U(Uniform(0.5f), 3);
  cv::Mat serial;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = effects.ToImage8U(Uniform(0.5f), 3);
  }
  EXPECT_EQ(cv::norm(a, serial, cv::NORM_INF), 0.0);                           // same seed, frame
  EXPECT_GT(cv::norm(a, effects.ToImage8U(Uniform(0.5f), 4), cv::NORM_L1), 0.0);  // next frame
  params.seed = 12;
  EXPECT_GT(cv::norm(a, CameraEffects(params).ToImage8U(Uniform(0.5f), 3), cv::NORM_L1), 0.0);
}

TEST(CameraEffectsTest, NoiseStatisticsFollowReadAndShotNoise) {
  CameraEffectsParams params;
  params.read_noise_sigma = 0.01;
  params.full_well_electrons = 1000.0;
  params.gain = 1.5;
  const CameraEffects effects(params);
  for (const float signal : {0.1f, 0.4f}) {
    cv::Mat image;
    effects.ToImage8U(Uniform(signal), 0).convertTo(image, CV_64F, 1.0 / 255.0);
    cv::Scalar mean, stddev;
    cv::meanStdDev(image, mean, stddev);
    const double expected_sigma = 1.5 * std::sqrt(0.01 * 0.01 + signal / 1000.0);
    // 76800 samples: the sample std is within ~0.5 % of the truth; quantization adds
    // (1/255)^2/12 in variance. 3 % covers both.
    EXPECT_NEAR(stddev[0], std::sqrt(expected_sigma * expected_sigma + 1.0 / (12 * 255.0 * 255.0)),
                0.03 * expected_sigma);
    EXPECT_NEAR(mean[0], 1.5 * signal, 2e-3);
  }
  EXPECT_THROW(CameraEffects(CameraEffectsParams{0.0}), std::invalid_argument);
}

// Sample correlation of a[i] and b[i] over all values of two equally sized 8-bit images.
double Correlation(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat x, y;
  a.clone().reshape(1, 1).convertTo(x, CV_64F);
  b.clone().reshape(1, 1).convertTo(y, CV_64F);
  x -= cv::mean(x)[0];
  y -= cv::mean(y)[0];
  return x.dot(y) / std::sqrt(x.dot(x) * y.dot(y));
}

TEST(CameraEffectsTest, NoiseIsGaussianAndIndependentBetweenValues) {
  // BGR at mid-grey with read noise only: sigma = 0.05 * 255 = 12.75 levels, no clipping within
  // the noise table's +-3.7 sigma.
  CameraEffectsParams params;
  params.read_noise_sigma = 0.05;
  const CameraEffects effects(params);
  const cv::Mat image = effects.ToImage8U(cv::Mat(240, 320, CV_32FC3, cv::Scalar::all(0.5)), 7);
  cv::Mat noise;
  image.reshape(1).convertTo(noise, CV_64F, 1.0 / 255.0, -0.5);
  cv::Mat squared, fourth;
  cv::multiply(noise, noise, squared);
  cv::multiply(squared, squared, fourth);
  const double variance = cv::mean(squared)[0];
  // 230400 values: the sample variance has a relative std of sqrt(2 / N) = 0.3 % (1.5 % is 5
  // sigma); quantization adds
  // (1/255)^2 / 12 (0.05 %). The kurtosis of a Gaussian is 3 (a uniform 1.8, a Laplacian 6);
  // its sample std is sqrt(24 / 230400) = 0.01, the table's tail cut lowers it to 2.99.
  EXPECT_NEAR(variance, 0.05 * 0.05, 0.015 * 0.05 * 0.05);
  EXPECT_NEAR(cv::mean(fourth)[0] / (variance * variance), 3.0, 0.06);
  // Neighbours along a row (channels interleaved: B-G, G-R, R-next B), across rows and between
  // the hashes' value groups: the sample correlation of independent values has std
  // 1 / sqrt(N) ~ 0.002; 0.01 is 5 sigma.
  const cv::Mat values = image.reshape(1);
  const int n = values.cols;
  for (const int shift : {1, 2, 3, 4, 5, 6}) {
    EXPECT_LT(std::abs(Correlation(values.colRange(0, n - shift), values.colRange(shift, n))), 0.01)
        << "shift " << shift;
  }
  EXPECT_LT(std::abs(Correlation(values.rowRange(0, 239), values.rowRange(1, 240))), 0.01);
}

TEST(CameraEffectsTest, MotionBlurSmearsAnEdgeOverTheImageMotion) {
  // A black/white vertical edge 2 m in front; the camera slides along x_C during the exposure.
  const auto camera = testing::MakeTestPinhole();
  Scene scene;
  SceneObject wall;
  wall.name = "wall";
  wall.primitive = Rectangle{{8.0, 8.0}, {}, {}};
  wall.material.texture = std::make_shared<const Texture>(Texture::Checkerboard(4.0));
  wall.material.color = Rgb::Ones();
  wall.T_WO = Pose({0, 0, 0}, {0.0, 0.0, 2.0});  // its edge u = 4 m is x = 0 in C
  scene.AddObject(wall);
  scene.lighting.ambient = 1.0f;
  scene.lighting.directional = 0.0f;
  // Image motion over the exposure: f * speed * exposure / Z = 420 * 0.5 * 0.0952 / 2 = 10 px.
  const double speed = 0.5;
  auto T_WC_at = [&](double t) { return Pose({0, 0, 0}, {speed * t, 0.0, 0.0}); };
  CameraEffectsParams params;
  params.exposure_s = 0.0952;
  params.motion_blur_subframes = 21;
  RayCaster caster;
  const CapturedFrame blurred = CameraEffects(params).Capture(caster, scene, *camera, T_WC_at, 0.0, 0);
  params.motion_blur_subframes = 1;
  const CapturedFrame sharp = CameraEffects(params).Capture(caster, scene, *camera, T_WC_at, 0.0, 0);
  auto ramp = [](const cv::Mat& image, double* centre) {
    // Pixels strictly between 10 % and 90 % of the contrast along row 240, and the 50 % crossing.
    const cv::Mat row = image.row(240);
    double lo, hi;
    cv::minMaxLoc(row, &lo, &hi);
    int count = 0;
    *centre = -1.0;
    for (int x = 0; x < row.cols; ++x) {
      const double v = (row.at<uint8_t>(x) - lo) / (hi - lo);
      count += v > 0.1 && v < 0.9;
      if (x > 0 && *centre < 0.0) {
        const double prev = (row.at<uint8_t>(x - 1) - lo) / (hi - lo);
        if ((prev - 0.5) * (v - 0.5) <= 0.0 && prev != v) *centre = x - 1 + (0.5 - prev) / (v - prev);
      }
    }
    return count;
  };
  double sharp_centre, blurred_centre;
  EXPECT_LE(ramp(sharp.frame.image, &sharp_centre), 2);
  // A 10 px linear ramp has 8 pixels between 10 % and 90 %; subframe steps allow +-1.
  const int blurred_width = ramp(blurred.frame.image, &blurred_centre);
  EXPECT_GE(blurred_width, 7);
  EXPECT_LE(blurred_width, 9);
  // The blur is centred on the mid-exposure edge position (x = cx = 375.5).
  EXPECT_NEAR(sharp_centre, 375.5, 0.3);
  EXPECT_NEAR(blurred_centre, 375.5, 0.5);
  // Ground truth comes from mid-exposure.
  EXPECT_EQ(cv::norm(blurred.depth_C, sharp.depth_C, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace aperture::sim
