#pragma once
// Scores a detected opening O against the true opening G (seed 002, Sec. IV-B, Table II), both
// CV_8UC1 masks of one size (non-zero = in the set), A' the complement of A:
//   overlap    lambda_D = |G ∩ O| / |G|, a detection counts when it is >= 0.75 (DR);
//   false neg. lambda_N = |G ∩ O'| / |G|   (the gap pixels missed: Fig. 10's yellow);
//   false pos. lambda_P = |G' ∩ O| / |G'|  (the wall pixels called opening: Fig. 10's red).
// The printed AFN formula reads |G' ∩ O'| / |G'|, which is 1 - lambda_P (the true-negative rate,
// ~1 for any good detection, against the paper's AFN = 0.14); the captions of Figs. 10 and 11
// define the false negatives as the missed gap pixels, which is what lambda_N measures here.
// AFN and AFP average lambda_N and lambda_P over the successful trials only (as the paper).
#include <opencv2/core/mat.hpp>

namespace aperture::perception {

struct OpeningScore {
  double overlap = 0.0;         // lambda_D
  double false_negative = 0.0;  // lambda_N
  double false_positive = 0.0;  // lambda_P
  bool detected() const { return overlap >= kDetectionOverlap; }
  static constexpr double kDetectionOverlap = 0.75;
};

// std::invalid_argument for empty or differently sized masks, or an empty G (nothing to find)
// or a G covering the whole image.
OpeningScore ScoreOpening(const cv::Mat& opening, const cv::Mat& truth);

}  // namespace aperture::perception
