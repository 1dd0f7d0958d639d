#pragma once
// Ground truth per patch and the depth errors of seed 003 Table I (after Michels et al. [13]):
//   E_ln       = |ln D - ln D_E|
//   E_relative = |D - D_E| / D
// averaged over the patches that have a surface (D finite). Both D and D_E are clipped to the
// labels' range [min_depth_m, max_depth_m] first: like the paper's laser truth (1-81 m), a depth
// beyond the range the classifier can name counts as the range's end.
#include <opencv2/core/mat.hpp>

#include "perception/mono_depth/mono_depth_features.h"

namespace aperture::perception {

// Median depth [m] of each patch of `depth_mm` (CV_16UC1, millimetres, 0 = no surface, as written
// by `aperture render`), CV_32FC1 grid.rows x grid.cols; pixels without a surface count as
// infinitely far, so a patch that is mostly sky is +inf. Throws std::invalid_argument for another
// type or when the image does not cover the grid.
cv::Mat PatchDepthFromMillimetres(const cv::Mat& depth_mm, const PatchGrid& grid);

struct DepthErrors {
  double e_ln_sum = 0.0;
  double e_relative_sum = 0.0;
  long patches = 0;  // patches with finite truth

  double MeanLn() const;        // NaN when no patch was scored
  double MeanRelative() const;  // NaN when no patch was scored
  DepthErrors& operator+=(const DepthErrors& other);
};

// Table I errors of `estimate_m` against `truth_m` (both CV_32FC1 of one size, [m]); throws
// std::invalid_argument on a type or size mismatch or a non-positive range.
DepthErrors CompareDepth(const cv::Mat& estimate_m, const cv::Mat& truth_m, double min_depth_m,
                         double max_depth_m);

}  // namespace aperture::perception
