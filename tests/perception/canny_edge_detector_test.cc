// CannyEdgeDetector against OpenCV's cv::Canny (+ cv::dilate), which it must reproduce exactly.
#include "perception/gap/canny_edge_detector.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

// Smoothed noise (texture with many weak gradients, the case the lazy evaluation speeds up),
// filled shapes of several contrasts and anti-aliased lines (all gradient directions, plateaus
// and ties in the magnitude), and a saturated corner (|dx| + |dy| at its maximum).
cv::Mat TestImage(int seed, int width = 320, int height = 240) {
  cv::Mat noise(height, width, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 60, 160);
  cv::Mat image;
  cv::GaussianBlur(noise, image, cv::Size(0, 0), 1.0 + 0.5 * (seed % 3));
  for (int k = 0; k < 12; ++k) {
    const cv::Point a(rng.uniform(0, width), rng.uniform(0, height));
    const cv::Point b(rng.uniform(0, width), rng.uniform(0, height));
    const int value = rng.uniform(0, 256);
    switch (k % 3) {
      case 0: cv::rectangle(image, a, b, cv::Scalar(value), cv::FILLED); break;
      case 1: cv::circle(image, a, rng.uniform(3, 60), cv::Scalar(value), cv::FILLED, cv::LINE_AA); break;
      default: cv::line(image, a, b, cv::Scalar(value), rng.uniform(1, 4), cv::LINE_AA); break;
    }
  }
  cv::rectangle(image, cv::Point(0, 0), cv::Point(width / 5, height / 5), cv::Scalar(255), cv::FILLED);
  cv::rectangle(image, cv::Point(width / 5, 0), cv::Point(width / 3, height / 5), cv::Scalar(0), cv::FILLED);
  return image;
}

int CountDifferences(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  return cv::countNonZero(a != b);
}

struct Thresholds {
  double low;
  double high;
};

TEST(CannyEdgeDetectorTest, MatchesOpenCvCannyOnWholeImages) {
  CannyEdgeDetector detector;  // one instance: buffers are reused across sizes and calls
  for (int seed = 0; seed < 6; ++seed) {
    const cv::Mat image = TestImage(seed, 320 + 17 * seed, 240 - 11 * seed);
    // Fractional thresholds are floored by both; low > high is swapped by both.
    for (const Thresholds t : {Thresholds{40, 120}, Thresholds{10, 30}, Thresholds{80.7, 240.2}, Thresholds{150, 50}}) {
      cv::Mat expected, edges;
      cv::Canny(image, expected, t.low, t.high);
      ASSERT_GT(cv::countNonZero(expected), 100);  // the comparison is not between empty images
      detector.Detect(image, cv::Rect(0, 0, image.cols, image.rows), t.low, t.high, false, &edges);
      EXPECT_EQ(CountDifferences(edges, expected), 0) << "seed " << seed << " thresholds " << t.low << "/" << t.high;
      cv::dilate(expected, expected, cv::Mat());
      detector.Detect(image, cv::Rect(0, 0, image.cols, image.rows), t.low, t.high, true, &edges);
      EXPECT_EQ(CountDifferences(edges, expected), 0) << "dilated, seed " << seed;
    }
  }
}

// cv::Canny on a sub-matrix treats it as an image of its own (border replicated): the ROI call
// must give the same, at the image's corners, along its edges and inside.
TEST(CannyEdgeDetectorTest, MatchesOpenCvCannyOnRegionsOfInterest) {
  CannyEdgeDetector detector;
  const cv::Mat image = TestImage(7, 400, 300);
  for (const cv::Rect roi : {cv::Rect(0, 0, 120, 90), cv::Rect(280, 210, 120, 90), cv::Rect(50, 40, 200, 150),
                             cv::Rect(0, 100, 400, 37), cv::Rect(399, 0, 1, 300), cv::Rect(10, 10, 2, 2)}) {
    cv::Mat expected, edges;
    cv::Canny(image(roi), expected, 40, 120);
    detector.Detect(image, roi, 40, 120, false, &edges);
    EXPECT_EQ(CountDifferences(edges, expected), 0) << "roi " << roi.x << "," << roi.y << " " << roi.width << "x" << roi.height;
    cv::dilate(expected, expected, cv::Mat());
    detector.Detect(image, roi, 40, 120, true, &edges);
    EXPECT_EQ(CountDifferences(edges, expected), 0) << "dilated roi " << roi.x << "," << roi.y;
  }
}

TEST(CannyEdgeDetectorTest, UniformImagesHaveNoEdges) {
  CannyEdgeDetector detector;
  cv::Mat edges;
  for (const int value : {0, 128, 255}) {
    const cv::Mat image(60, 80, CV_8UC1, cv::Scalar(value));
    detector.Detect(image, cv::Rect(0, 0, 80, 60), 1, 2, true, &edges);
    EXPECT_EQ(cv::countNonZero(edges), 0);
  }
}

TEST(CannyEdgeDetectorTest, RejectsWrongImagesAndRegions) {
  CannyEdgeDetector detector;
  cv::Mat edges;
  const cv::Mat color(60, 80, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_THROW(detector.Detect(color, cv::Rect(0, 0, 80, 60), 40, 120, false, &edges), std::invalid_argument);
  const cv::Mat gray(60, 80, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(detector.Detect(gray, cv::Rect(70, 0, 20, 60), 40, 120, false, &edges), std::invalid_argument);
  EXPECT_THROW(detector.Detect(gray, cv::Rect(0, 0, 0, 60), 40, 120, false, &edges), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
