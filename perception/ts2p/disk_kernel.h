#pragma once
// The disc-shaped structuring element of the TS2P masks' morphology (opening, closing, dilation
// of the segmentation and of the label sets): a filled ellipse of diameter 2 radius_px + 1.
#include <opencv2/imgproc.hpp>

namespace aperture::perception {

inline cv::Mat DiskKernel(int radius_px) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                   cv::Size(2 * radius_px + 1, 2 * radius_px + 1));
}

}  // namespace aperture::perception
