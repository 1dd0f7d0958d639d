#include "perception/ts2p/opening_score.h"

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace aperture::perception {

OpeningScore ScoreOpening(const cv::Mat& opening, const cv::Mat& truth) {
  if (opening.empty() || truth.empty() || opening.size() != truth.size() ||
      opening.type() != CV_8UC1 || truth.type() != CV_8UC1) {
    throw std::invalid_argument("ScoreOpening needs two CV_8UC1 masks of one size, got " +
                                std::to_string(opening.cols) + "x" + std::to_string(opening.rows) +
                                " and " + std::to_string(truth.cols) + "x" +
                                std::to_string(truth.rows));
  }
  const double g = cv::countNonZero(truth);
  const double not_g = static_cast<double>(truth.total()) - g;
  if (g == 0.0 || not_g == 0.0) {
    throw std::invalid_argument(
        "ScoreOpening: the true opening is empty or covers the whole image; check the masks");
  }
  cv::Mat g_and_o;
  cv::bitwise_and(opening != 0, truth != 0, g_and_o);
  const double hit = cv::countNonZero(g_and_o);
  const double o = cv::countNonZero(opening);
  OpeningScore score;
  score.overlap = hit / g;
  score.false_negative = (g - hit) / g;
  score.false_positive = (o - hit) / not_g;
  return score;
}

}  // namespace aperture::perception
