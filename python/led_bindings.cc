// aperture.LedConfiguration, aperture.LedTracker, aperture.LedTrackResult (perception/led, thesis
// App. C).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "perception/led/led_tracker.h"
#include "python/bindings.h"
#include "python/numpy_image.h"

namespace aperture::python {
namespace py = pybind11;
using perception::LedConfiguration;
using perception::LedTracker;
using perception::LedTrackResult;

void BindLedTracker(py::module_& m) {
  py::class_<LedConfiguration>(m, "LedConfiguration", "LED positions p_T [m] on the target.")
      .def(py::init<std::vector<Eigen::Vector3d>, std::string>(), py::arg("p_T"),
           py::arg("source") = "python")
      .def_static("load", &LedConfiguration::Load, py::arg("path"),
                  "Reads `leds: [[x, y, z], ...]` from a YAML file.")
      .def_static("default", &LedConfiguration::Default)
      .def_property_readonly("p_T", &LedConfiguration::p_T)
      .def("__len__", &LedConfiguration::size);

  py::class_<LedTrackResult>(m, "LedTrackResult")
      .def_property_readonly(
          "status",
          [](const LedTrackResult& r) { return perception::LedTrackStatusName(r.status); })
      .def_property_readonly("has_pose", &LedTrackResult::has_pose)
      .def_property_readonly(
          "T_CT",
          [](const LedTrackResult& r) -> std::optional<Eigen::Matrix4d> {
            if (!r.T_CT) return std::nullopt;
            return Eigen::Matrix4d(r.T_CT->matrix());
          },
          "Target in the camera frame (4 x 4), None without a pose")
      .def_readonly("covariance", &LedTrackResult::covariance)
      .def_property_readonly("detections_px",
                             [](const LedTrackResult& r) {
                               Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> px(
                                   r.detections.size(), 2);
                               for (size_t i = 0; i < r.detections.size(); ++i) {
                                 px.row(i) = r.detections[i].px.transpose();
                               }
                               return px;
                             })
      .def_readonly("rms_px", &LedTrackResult::rms_px)
      .def("__repr__", [](const LedTrackResult& r) {
        return "<aperture.LedTrackResult " + perception::LedTrackStatusName(r.status) + ">";
      });

  py::class_<LedTracker>(m, "LedTracker",
                         "Infrared-LED pose tracker (thesis App. C): detection, P3P correspondence "
                         "search, prediction, Gauss-Newton refinement.")
      .def(py::init([](const LedConfiguration& configuration,
                       std::shared_ptr<perception::CameraModel> camera) {
             return std::make_unique<LedTracker>(configuration, std::move(camera));
           }),
           py::arg("configuration"), py::arg("camera"))
      .def(
          "track",
          [](LedTracker& tracker, const py::array& image, double t_s) {
            return tracker.Track(ImageView(image, "LedTracker.track image"), t_s);
          },
          py::arg("image"), py::arg("t_s"),
          "Tracks the target in one uint8 image at time t_s [s] (increasing).")
      .def("reset", &LedTracker::Reset);
}

}  // namespace aperture::python
