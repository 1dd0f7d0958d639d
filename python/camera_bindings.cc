// aperture.CameraModel, aperture.create_camera_model, aperture.CameraCalibration,
// aperture.load_calibration / save_calibration (perception/camera).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "perception/camera/calibration_io.h"
#include "perception/camera/camera_factory.h"
#include "python/bindings.h"

namespace aperture::python {
namespace py = pybind11;
using perception::CameraCalibration;
using perception::CameraModel;

namespace {

using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Points2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

// Projects N points p_C (rows); returns (pixels N x 2, valid N) like CameraModel::Project.
py::tuple Project(const CameraModel& camera, const Points3& p_C) {
  Points2 px(p_C.rows(), 2);
  std::vector<bool> valid(p_C.rows());
  for (Eigen::Index i = 0; i < p_C.rows(); ++i) {
    Eigen::Vector2d pixel;
    valid[i] = camera.Project(p_C.row(i).transpose(), &pixel);
    px.row(i) = pixel.transpose();
  }
  return py::make_tuple(px, py::array(py::cast(valid)));
}

Points3 Unproject(const CameraModel& camera, const Points2& px) {
  Points3 f_C(px.rows(), 3);
  for (Eigen::Index i = 0; i < px.rows(); ++i) {
    f_C.row(i) = camera.Unproject(px.row(i).transpose()).transpose();
  }
  return f_C;
}

}  // namespace

void BindCameras(py::module_& m) {
  py::class_<CameraModel, std::shared_ptr<CameraModel>>(
      m, "CameraModel",
      "A calibrated camera (pinhole, radtan or equidistant fisheye), OpenCV axes: x right, y down, "
      "z forward.")
      .def_property_readonly("width", &CameraModel::width)
      .def_property_readonly("height", &CameraModel::height)
      .def_property_readonly("model_name", &CameraModel::model_name)
      .def_property_readonly("intrinsics", &CameraModel::intrinsics, "[fx, fy, cx, cy] in px")
      .def_property_readonly("distortion", &CameraModel::distortion)
      .def("project", &Project, py::arg("p_C"),
           "Projects points p_C (N x 3, metres, camera frame) to pixels: returns (px N x 2, valid "
           "N bool) where valid is False behind the camera or outside the model's domain.")
      .def("unproject", &Unproject, py::arg("px"),
           "Unit bearings f_C (N x 3) through pixels px (N x 2).")
      .def(
          "scaled",
          [](const CameraModel& camera, int width, int height) {
            return std::shared_ptr<CameraModel>(camera.Scaled(width, height));
          },
          py::arg("width"), py::arg("height"), "The same lens at another image size.")
      .def("__repr__", [](const CameraModel& camera) {
        return "<aperture.CameraModel " + camera.model_name() + " " +
               std::to_string(camera.width()) + "x" + std::to_string(camera.height()) + ">";
      });

  m.def(
      "create_camera_model",
      [](const std::string& model, int width, int height, const Eigen::VectorXd& intrinsics,
         const Eigen::VectorXd& distortion) {
        return std::shared_ptr<CameraModel>(
            perception::CreateCameraModel(model, width, height, intrinsics, distortion));
      },
      py::arg("model"), py::arg("width"), py::arg("height"), py::arg("intrinsics"),
      py::arg("distortion") = Eigen::VectorXd(),
      "A camera model by name ('pinhole', 'radtan', 'equidistant'); intrinsics [fx, fy, cx, cy] "
      "in px. Raises ValueError naming a bad name or parameter.");

  py::class_<CameraCalibration>(m, "CameraCalibration")
      .def_property_readonly(
          "camera",
          [](const CameraCalibration& c) { return std::const_pointer_cast<CameraModel>(c.camera); })
      .def_property_readonly(
          "T_BC", [](const CameraCalibration& c) { return Eigen::Matrix4d(c.T_BC.matrix()); },
          "Camera-to-body extrinsics (4 x 4; identity when the file has none)")
      .def_readonly("name", &CameraCalibration::name)
      .def_readonly("source_path", &CameraCalibration::source_path);

  m.def("load_calibration", &perception::LoadCameraCalibration, py::arg("path"),
        py::arg("kalibr_camera") = "",
        "Loads an OpenCV FileStorage, ROS camera_info or Kalibr camchain YAML (format detected "
        "from the content; kalibr_camera picks the camchain's camera, empty: its only one).");
  m.def(
      "save_calibration",
      [](const CameraModel& camera, const std::string& path, const std::string& format,
         const std::string& name, const Eigen::Matrix4d& T_BC) {
        CameraCalibration calibration;
        calibration.camera = camera.Clone();
        calibration.name = name;
        calibration.T_BC.matrix() = T_BC;
        perception::SaveCameraCalibration(calibration, path,
                                          perception::ParseCalibrationFormat(format));
      },
      py::arg("camera"), py::arg("path"), py::arg("format") = "opencv", py::arg("name") = "",
      py::arg("T_BC") = Eigen::Matrix4d::Identity().eval(),
      "Writes the camera (and the camera-to-body extrinsics T_BC) as 'opencv', 'ros' or "
      "'kalibr' YAML.");
}

}  // namespace aperture::python
