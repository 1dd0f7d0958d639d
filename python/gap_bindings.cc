// aperture.GapDetectorParams, aperture.GapDetector, aperture.GapDetection (perception/gap, seed 000
// Sec. III-A).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "perception/gap/gap_detector.h"
#include "python/bindings.h"
#include "python/numpy_image.h"

namespace aperture::python {
namespace py = pybind11;
using perception::GapDetection;
using perception::GapDetector;
using perception::GapDetectorParams;

namespace {

Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> Rows(
    const std::vector<Eigen::Vector2d>& points) {
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> rows(points.size(), 2);
  for (size_t i = 0; i < points.size(); ++i) rows.row(i) = points[i].transpose();
  return rows;
}

}  // namespace

void BindGapDetector(py::module_& m) {
  py::class_<GapDetectorParams>(m, "GapDetectorParams",
                                "Pattern geometry [m] and detector thresholds (gap_detector.h).")
      .def(py::init<>())
      .def_readwrite("opening_size_m", &GapDetectorParams::opening_size_m)
      .def_readwrite("inner_size_m", &GapDetectorParams::inner_size_m)
      .def_readwrite("outer_size_m", &GapDetectorParams::outer_size_m)
      .def_readwrite("canny_low", &GapDetectorParams::canny_low)
      .def_readwrite("canny_high", &GapDetectorParams::canny_high)
      .def_readwrite("min_contrast", &GapDetectorParams::min_contrast)
      .def_readwrite("max_corner_rms_px", &GapDetectorParams::max_corner_rms_px)
      .def_readwrite("pixel_sigma_px", &GapDetectorParams::pixel_sigma_px)
      .def_readwrite("use_roi", &GapDetectorParams::use_roi);

  py::class_<GapDetection>(m, "GapDetection")
      .def_property_readonly(
          "status",
          [](const GapDetection& d) { return perception::GapDetectionStatusName(d.status); })
      .def_property_readonly("detected", &GapDetection::detected)
      .def_property_readonly(
          "T_CG", [](const GapDetection& d) { return Eigen::Matrix4d(d.T_CG.matrix()); },
          "Gap in the camera frame (4 x 4), identity when not detected")
      .def_readonly("covariance", &GapDetection::covariance, "6 x 6 of [p_CG [m]; rotation [rad]]")
      .def_readonly("corner_rms_px", &GapDetection::corner_rms_px)
      .def_readonly("edge_rms_px", &GapDetection::edge_rms_px)
      .def_property_readonly(
          "corners_px", [](const GapDetection& d) { return Rows(d.corners_px); },
          "8 x 2 sub-pixel corners: outer then inner")
      .def_readonly("from_roi", &GapDetection::from_roi)
      .def("__repr__", [](const GapDetection& d) {
        return "<aperture.GapDetection " + perception::GapDetectionStatusName(d.status) + ">";
      });

  py::class_<GapDetector>(m, "GapDetector",
                          "Patterned-gap detector (Falanga et al. 2017, Sec. III-A); tracks an ROI "
                          "between calls to detect().")
      .def(py::init([](std::shared_ptr<perception::CameraModel> camera,
                       const GapDetectorParams& params) {
             return std::make_unique<GapDetector>(params, std::move(camera));
           }),
           py::arg("camera"), py::arg("params") = GapDetectorParams{})
      .def(
          "detect",
          [](GapDetector& detector, const py::array& image) {
            return detector.Detect(ImageView(image, "GapDetector.detect image"));
          },
          py::arg("image"),
          "Detects the gap in a uint8 (H, W) or (H, W, 3) BGR image of the camera's size.")
      .def("reset_tracking", &GapDetector::ResetTracking);
}

}  // namespace aperture::python
