#pragma once
// Ground-truth images as 16-bit files (what `aperture render` writes as PNG):
//   depth: z_C in millimetres, rounded to the nearest mm; 0 = no surface (sky, +inf, NaN);
//          depths >= 65.535 m saturate at 65535.
//   ids:   Scene object id (0 = sky); ids > 65535 saturate (scenes have far fewer objects).
// And false-colour previews for reports (8-bit BGR).
#include <opencv2/core/mat.hpp>

namespace aperture::sim {

// depth_C: CV_32FC1 [m] -> CV_16UC1 [mm]. std::invalid_argument for another type.
cv::Mat DepthToMillimetres16U(const cv::Mat& depth_C);
// object_id: CV_32SC1 -> CV_16UC1. std::invalid_argument for another type.
cv::Mat ObjectIdsTo16U(const cv::Mat& object_id);

// Depth preview: near bright/warm to far dark (colormap over [0, max_depth_m]), no surface black.
cv::Mat DepthPreview(const cv::Mat& depth_C, double max_depth_m);
// Id preview: a fixed pseudo-random colour per id, sky black.
cv::Mat ObjectIdPreview(const cv::Mat& object_id);

}  // namespace aperture::sim
