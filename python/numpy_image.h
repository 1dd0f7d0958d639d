#pragma once
// NumPy <-> cv::Mat for the Python bindings. Images cross as uint8 arrays: (H, W) gray or
// (H, W, 3) BGR, the OpenCV convention, so arrays from cv2.imread pass unchanged.
#include <pybind11/numpy.h>

#include <opencv2/core/mat.hpp>
#include <string>

namespace aperture::python {

// A cv::Mat viewing `array` (no copy; valid while `array` lives). Throws std::invalid_argument
// naming `what` when the array is not uint8 (H, W) or (H, W, 3), or not C-contiguous.
cv::Mat ImageView(const pybind11::array& array, const std::string& what);

// A NumPy copy of an 8-bit 1- or 3-channel image.
pybind11::array_t<uint8_t> ToNumpy(const cv::Mat& image);

}  // namespace aperture::python
