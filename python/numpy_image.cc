#include "python/numpy_image.h"

#include <cstring>
#include <stdexcept>
#include <vector>

namespace aperture::python {
namespace py = pybind11;

cv::Mat ImageView(const py::array& array, const std::string& what) {
  const bool gray = array.ndim() == 2;
  const bool bgr = array.ndim() == 3 && array.shape(2) == 3;
  if (!array.dtype().is(py::dtype::of<uint8_t>()) || !(gray || bgr)) {
    throw std::invalid_argument(
        what +
        ": expected a uint8 image of shape (H, W) or (H, W, 3), got "
        "dtype " +
        std::string(py::str(array.dtype())) + " with " + std::to_string(array.ndim()) +
        " dimensions; convert with numpy.asarray(image, dtype=numpy.uint8)");
  }
  if (!(array.flags() & py::array::c_style)) {
    throw std::invalid_argument(what +
                                ": the image array is not C-contiguous; pass "
                                "numpy.ascontiguousarray(image)");
  }
  return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
                 gray ? CV_8UC1 : CV_8UC3, const_cast<void*>(array.data()));
}

py::array_t<uint8_t> ToNumpy(const cv::Mat& image) {
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3)) {
    throw std::invalid_argument("ToNumpy: expected an 8-bit 1- or 3-channel image");
  }
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (image.channels() == 3) shape.push_back(3);
  py::array_t<uint8_t> array(shape);
  const cv::Mat continuous = image.isContinuous() ? image : image.clone();
  std::memcpy(array.mutable_data(), continuous.data, image.total() * image.elemSize());
  return array;
}

}  // namespace aperture::python
