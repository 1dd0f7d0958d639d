#pragma once
// Per-image exposure and sharpness statistics: a normalised intensity histogram, mean intensity,
// the fractions of over- and under-exposed pixels, and the variance of the Laplacian as a
// sharpness measure (it drops with defocus and motion blur; Pech-Pacheco et al., ICPR 2000).
// Colour input is converted to gray first.
#include <opencv2/core/mat.hpp>
#include <vector>

namespace aperture::perception {

struct ImageQualityParams {
  // Histogram bins over the 8-bit range; bin b holds intensities v with v * bins / 256 == b.
  // 16 keeps the per-frame CSV readable while still showing clipping and the exposure shape.
  int histogram_bins = 16;
  // Pixels >= over_exposed_level count as over-exposed, <= under_exposed_level as under-exposed.
  // 250 / 5 leave a margin for sensor noise around the clipping values 255 / 0.
  int over_exposed_level = 250;
  int under_exposed_level = 5;
};

struct ImageQuality {
  std::vector<double> histogram;     // histogram_bins entries, sums to 1
  double mean_intensity = 0.0;       // [0, 255]
  double over_exposed_ratio = 0.0;   // fraction of pixels >= over_exposed_level
  double under_exposed_ratio = 0.0;  // fraction of pixels <= under_exposed_level
  // Variance of the 3x3 Laplacian (cv::Laplacian, ksize 1, CV_64F) [intensity^2]; 0 for a
  // uniform image.
  double sharpness_laplacian_var = 0.0;
};

class ImageQualityAnalyzer {
 public:
  // Throws std::invalid_argument if histogram_bins is not in [1, 256] or a level is outside
  // [0, 255].
  explicit ImageQualityAnalyzer(const ImageQualityParams& params = {});

  // `image`: CV_8UC1 gray, CV_8UC3 BGR or CV_8UC4 BGRA, non-empty (else std::invalid_argument).
  // Reuses internal buffers: not safe to call concurrently on one analyzer.
  ImageQuality Analyze(const cv::Mat& image);

  const ImageQualityParams& params() const { return params_; }

 private:
  ImageQualityParams params_;
  cv::Mat gray_;       // conversion buffer for colour input
  cv::Mat laplacian_;  // CV_64F
};

}  // namespace aperture::perception
