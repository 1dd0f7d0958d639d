#include "perception/camera/calibration_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "config/regular_file.h"
#include "config/usage_error.h"
#include "perception/camera/camera_factory.h"

namespace aperture::perception {
namespace {

[[noreturn]] void Fail(const std::string& path, const std::string& field,
                       const std::string& problem) {
  throw std::invalid_argument("calibration file '" + path + "', field '" + field + "': " + problem);
}

// Everything a file describes, in our names, before the camera model is built.
struct ParsedCalibration {
  std::string model;  // pinhole | radtan | equidistant
  int width = 0;
  int height = 0;
  Eigen::Vector4d intrinsics = Eigen::Vector4d::Zero();  // fx fy cx cy
  Eigen::VectorXd distortion;
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  std::string name;
};

CameraCalibration Build(const ParsedCalibration& parsed, const std::string& path) {
  CameraCalibration calib;
  try {
    calib.camera = CreateCameraModel(parsed.model, parsed.width, parsed.height, parsed.intrinsics,
                                     parsed.distortion);
  } catch (const std::invalid_argument& e) {
    // The factory names the field (fx, distortion, width, ...); add the file.
    throw std::invalid_argument("calibration file '" + path + "': " + e.what());
  }
  calib.T_BC = parsed.T_BC;
  calib.name = parsed.name;
  calib.source_path = path;
  return calib;
}

// A rows x cols matrix stored row-major as a flat list, as OpenCV and ROS write it.
struct FlatMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> data;
};

void CheckMatrixShape(const FlatMatrix& m, const std::string& path, const std::string& field) {
  if (m.rows < 0 || m.cols < 0 ||
      static_cast<size_t>(m.rows) * static_cast<size_t>(m.cols) != m.data.size()) {
    Fail(path, field,
         "rows*cols = " + std::to_string(m.rows) + "*" + std::to_string(m.cols) +
             " does not match the " + std::to_string(m.data.size()) + " values in data");
  }
}

Eigen::Vector4d IntrinsicsFromCameraMatrix(const FlatMatrix& K, const std::string& path,
                                           const std::string& field) {
  CheckMatrixShape(K, path, field);
  if (K.rows != 3 || K.cols != 3) {
    Fail(path, field,
         "expected a 3x3 matrix, got " + std::to_string(K.rows) + "x" + std::to_string(K.cols));
  }
  const std::vector<double>& k = K.data;
  // Our models have no skew; a tiny skew is calibration noise, anything larger is another model.
  if (std::abs(k[1]) > 1e-9 * std::abs(k[0]) || k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 ||
      k[8] != 1.0) {
    Fail(path, field, "expected [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  }
  return {k[0], k[4], k[2], k[5]};
}

Eigen::VectorXd VectorFromMatrix(const FlatMatrix& m, const std::string& path,
                                 const std::string& field) {
  CheckMatrixShape(m, path, field);
  if (m.rows > 1 && m.cols > 1) {
    Fail(path, field,
         "expected a row or column vector, got " + std::to_string(m.rows) + "x" +
             std::to_string(m.cols));
  }
  return Eigen::Map<const Eigen::VectorXd>(m.data.data(), static_cast<Eigen::Index>(m.data.size()));
}

Eigen::Isometry3d TransformFromMatrix(const FlatMatrix& m, const std::string& path,
                                      const std::string& field) {
  CheckMatrixShape(m, path, field);
  if (m.rows != 4 || m.cols != 4) {
    Fail(path, field,
         "expected a 4x4 matrix, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
  }
  const Eigen::Matrix4d T =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m.data.data());
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  // Calibration tools write rotations to ~1e-9; 1e-6 rejects scaled or sheared matrices only.
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1) ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      R.determinant() < 0.0) {
    Fail(path, field, "expected a rigid transform [R t; 0 0 0 1] with R a rotation matrix");
  }
  Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
  iso.matrix() = T;
  return iso;
}

FlatMatrix ToFlat(const Eigen::MatrixXd& m) {
  FlatMatrix flat{static_cast<int>(m.rows()), static_cast<int>(m.cols()), {}};
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) flat.data.push_back(m(r, c));
  return flat;
}

Eigen::Matrix3d CameraMatrix(const Eigen::Vector4d& k) {
  Eigen::Matrix3d K;
  K << k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1;
  return K;
}

// ---------------------------------------------------------------- OpenCV FileStorage ----------

cv::FileNode RequireNode(const cv::FileStorage& fs, const std::string& key,
                         const std::string& path) {
  cv::FileNode node = fs[key];
  if (node.empty() || node.isNone()) Fail(path, key, "missing key");
  return node;
}

int ReadInt(const cv::FileStorage& fs, const std::string& key, const std::string& path) {
  const cv::FileNode node = RequireNode(fs, key, path);
  if (!node.isInt()) Fail(path, key, "expected an integer");
  return static_cast<int>(node);
}

FlatMatrix ReadOpenCvMatrix(const cv::FileNode& node, const std::string& path,
                            const std::string& field) {
  if (!node.isMap()) Fail(path, field, "expected an !!opencv-matrix with rows, cols, data");
  FlatMatrix m;
  for (const char* key : {"rows", "cols", "data"}) {
    if (node[key].empty()) Fail(path, field + "." + key, "missing key");
  }
  if (!node["rows"].isInt() || !node["cols"].isInt())
    Fail(path, field, "rows and cols must be integers");
  m.rows = static_cast<int>(node["rows"]);
  m.cols = static_cast<int>(node["cols"]);
  const cv::FileNode data = node["data"];
  if (!data.isSeq()) Fail(path, field + ".data", "expected a list of numbers");
  for (const cv::FileNode& value : data) {
    if (!value.isInt() && !value.isReal()) Fail(path, field + ".data", "expected numbers");
    m.data.push_back(static_cast<double>(value));
  }
  return m;
}

CameraCalibration LoadOpenCv(const std::string& path) {
  // OpenCV 4.6's base64 reader (cv::FileStorage::Impl::parseBase64) can loop forever on a
  // malformed `!!binary` value (found by fuzzing); calibration files hold a few numbers as text.
  std::ifstream file(path);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (text.find("!!binary") != std::string::npos) {
    Fail(path, "(file)",
         "base64 (!!binary) data is not supported in a calibration file; write the matrices as "
         "text (cv::FileStorage without the BASE64 flag)");
  }
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    Fail(path, "(file)", "not a valid OpenCV FileStorage file: " + e.err);
  } catch (const std::length_error& e) {  // its parser on an empty key before a '[' (fuzzing)
    Fail(path, "(file)",
         std::string("not a valid OpenCV FileStorage file (its parser failed: ") + e.what() + ")");
  }
  if (!fs.isOpened()) Fail(path, "(file)", "cannot be opened as OpenCV FileStorage");
  // cv::FileStorage::operator[] throws cv::Exception (an assertion naming no file) on a root that
  // is not a map.
  if (!fs.root().isMap()) {
    Fail(path, "(file)",
         "the top level must be a map of keys (image_width, image_height, camera_matrix, ...)");
  }
  ParsedCalibration parsed;
  parsed.width = ReadInt(fs, "image_width", path);
  parsed.height = ReadInt(fs, "image_height", path);
  parsed.intrinsics = IntrinsicsFromCameraMatrix(
      ReadOpenCvMatrix(RequireNode(fs, "camera_matrix", path), path, "camera_matrix"), path,
      "camera_matrix");
  parsed.distortion =
      VectorFromMatrix(ReadOpenCvMatrix(RequireNode(fs, "distortion_coefficients", path), path,
                                        "distortion_coefficients"),
                       path, "distortion_coefficients");
  parsed.model = "radtan";  // OpenCV's calibration sample writes no model: plumb bob.
  const cv::FileNode model = fs["distortion_model"];
  if (!model.empty() && !model.isNone()) {
    if (!model.isString()) Fail(path, "distortion_model", "expected radtan|equidistant|pinhole");
    parsed.model = static_cast<std::string>(model);
    if (parsed.model != "radtan" && parsed.model != "equidistant" && parsed.model != "pinhole") {
      Fail(path, "distortion_model",
           "unknown model '" + parsed.model + "'; expected radtan|equidistant|pinhole");
    }
  }
  if (parsed.model == "pinhole") {
    // Saved with zero coefficients so OpenCV tools read it; they must be zero.
    if (parsed.distortion.size() > 0 && parsed.distortion.cwiseAbs().maxCoeff() != 0.0)
      Fail(path, "distortion_coefficients", "must be all zero for distortion_model pinhole");
    parsed.distortion.resize(0);
  }
  const cv::FileNode name = fs["camera_name"];
  if (!name.empty() && name.isString()) parsed.name = static_cast<std::string>(name);
  const cv::FileNode T_BC = fs["T_BC"];
  if (!T_BC.empty() && !T_BC.isNone())
    parsed.T_BC = TransformFromMatrix(ReadOpenCvMatrix(T_BC, path, "T_BC"), path, "T_BC");
  if (parsed.distortion.size() >= 8) {
    Fail(path, "distortion_coefficients",
         std::to_string(parsed.distortion.size()) +
             " coefficients (OpenCV rational/thin-prism model) are not supported; calibrate "
             "with 5 coefficients (k1 k2 p1 p2 k3)");
  }
  return Build(parsed, path);
}

cv::Mat ToCv(const Eigen::MatrixXd& m) {
  cv::Mat out(static_cast<int>(m.rows()), static_cast<int>(m.cols()), CV_64F);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) out.at<double>(r, c) = m(r, c);
  return out;
}

void SaveOpenCv(const CameraCalibration& calib, const std::string& path) {
  const CameraModel& cam = *calib.camera;
  cv::FileStorage fs(path, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
  if (!fs.isOpened()) throw std::runtime_error("cannot write calibration file '" + path + "'");
  fs << "image_width" << cam.width() << "image_height" << cam.height();
  fs << "camera_name" << calib.name;
  fs << "camera_matrix" << ToCv(CameraMatrix(cam.intrinsics()));
  fs << "distortion_model" << cam.model_name();
  // A pinhole camera is written with 5 zero coefficients so that OpenCV tools read it.
  const Eigen::VectorXd d =
      cam.model_name() == "pinhole" ? Eigen::VectorXd::Zero(5) : cam.distortion();
  fs << "distortion_coefficients" << ToCv(d);
  fs << "T_BC" << ToCv(calib.T_BC.matrix());
}

// ---------------------------------------------------------------- yaml-cpp helpers -----------

YAML::Node LoadYaml(const std::string& path) {
  config::RequireRegularFileIfPresent(path, "calibration file");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    Fail(path, "(file)", "cannot be opened; check the path");
  } catch (const YAML::Exception& e) {
    Fail(path, "(file)", std::string("is not valid YAML: ") + e.what());
  }
}

YAML::Node Require(const YAML::Node& parent, const std::string& key, const std::string& path,
                   const std::string& field) {
  if (!parent.IsMap() || !parent[key]) Fail(path, field, "missing key");
  return parent[key];
}

template <typename T>
T As(const YAML::Node& node, const std::string& path, const std::string& field,
     const std::string& expected) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    Fail(path, field, "expected " + expected);
  }
}

FlatMatrix ReadRosMatrix(const YAML::Node& parent, const std::string& key,
                         const std::string& path) {
  const YAML::Node node = Require(parent, key, path, key);
  FlatMatrix m;
  m.rows = As<int>(Require(node, "rows", path, key + ".rows"), path, key + ".rows", "an integer");
  m.cols = As<int>(Require(node, "cols", path, key + ".cols"), path, key + ".cols", "an integer");
  m.data = As<std::vector<double>>(Require(node, "data", path, key + ".data"), path, key + ".data",
                                   "a list of numbers");
  return m;
}

void WriteYamlFile(const YAML::Emitter& out, const std::string& path) {
  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("cannot write calibration file '" + path + "'");
}

void EmitRosMatrix(YAML::Emitter& out, const std::string& key, const Eigen::MatrixXd& m) {
  const FlatMatrix flat = ToFlat(m);
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rows" << YAML::Value << flat.rows;
  out << YAML::Key << "cols" << YAML::Value << flat.cols;
  out << YAML::Key << "data" << YAML::Value << YAML::Flow << flat.data;
  out << YAML::EndMap;
}

// ---------------------------------------------------------------- ROS camera_info ------------

// The camera fields every ROS camera_info carries, in our names; "" or a plumb_bob with zero
// coefficients is what ROS writes for a camera without distortion.
ParsedCalibration ParseRosCamera(int width, int height, const FlatMatrix& K,
                                 const std::string& distortion_model, const FlatMatrix& D,
                                 const std::string& path) {
  ParsedCalibration parsed;
  parsed.width = width;
  parsed.height = height;
  parsed.intrinsics = IntrinsicsFromCameraMatrix(K, path, "camera_matrix");
  if (distortion_model == "plumb_bob") {
    parsed.model = "radtan";
  } else if (distortion_model == "equidistant") {
    parsed.model = "equidistant";
  } else if (distortion_model.empty() && D.data.empty()) {
    parsed.model = "pinhole";
    return parsed;
  } else {
    Fail(path, "distortion_model",
         "unsupported model '" + distortion_model + "'; expected plumb_bob or equidistant");
  }
  parsed.distortion = VectorFromMatrix(D, path, "distortion_coefficients");
  return parsed;
}

CameraCalibration LoadRos(const std::string& path) {
  const YAML::Node root = LoadYaml(path);
  const int width =
      As<int>(Require(root, "image_width", path, "image_width"), path, "image_width", "an integer");
  const int height = As<int>(Require(root, "image_height", path, "image_height"), path,
                             "image_height", "an integer");
  const std::string model =
      As<std::string>(Require(root, "distortion_model", path, "distortion_model"), path,
                      "distortion_model", "a string");
  ParsedCalibration parsed =
      ParseRosCamera(width, height, ReadRosMatrix(root, "camera_matrix", path), model,
                     ReadRosMatrix(root, "distortion_coefficients", path), path);
  if (root["camera_name"])
    parsed.name = As<std::string>(root["camera_name"], path, "camera_name", "a string");
  if (root["T_BC"])
    parsed.T_BC = TransformFromMatrix(ReadRosMatrix(root, "T_BC", path), path, "T_BC");
  return Build(parsed, path);
}

void SaveRos(const CameraCalibration& calib, const std::string& path) {
  const CameraModel& cam = *calib.camera;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "image_width" << YAML::Value << cam.width();
  out << YAML::Key << "image_height" << YAML::Value << cam.height();
  out << YAML::Key << "camera_name" << YAML::Value << calib.name;
  const Eigen::Matrix3d K = CameraMatrix(cam.intrinsics());
  EmitRosMatrix(out, "camera_matrix", K);
  const bool equidistant = cam.model_name() == "equidistant";
  out << YAML::Key << "distortion_model" << YAML::Value
      << (equidistant ? "equidistant" : "plumb_bob");
  // ROS has no distortion-free model: a pinhole camera is plumb_bob with zero coefficients.
  const Eigen::VectorXd d =
      cam.model_name() == "pinhole" ? Eigen::VectorXd::Zero(5) : cam.distortion();
  EmitRosMatrix(out, "distortion_coefficients", d.transpose());
  EmitRosMatrix(out, "rectification_matrix", Eigen::Matrix3d::Identity());
  Eigen::Matrix<double, 3, 4> P = Eigen::Matrix<double, 3, 4>::Zero();
  P.leftCols<3>() = K;
  EmitRosMatrix(out, "projection_matrix", P);
  EmitRosMatrix(out, "T_BC", calib.T_BC.matrix());
  out << YAML::EndMap;
  WriteYamlFile(out, path);
}

// ---------------------------------------------------------------- Kalibr camchain ------------

// The camera of a camchain: `requested`, else the only camN key of the file.
std::string KalibrCameraKey(const YAML::Node& root, const std::string& path,
                            const std::string& requested) {
  std::vector<std::string> cameras;
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (key.size() > 3 && key.compare(0, 3, "cam") == 0 &&
        key.find_first_not_of("0123456789", 3) == std::string::npos) {
      cameras.push_back(key);
    }
  }
  std::string names;
  for (const std::string& name : cameras) names += (names.empty() ? "" : ", ") + name;
  // The choice of camera is the caller's (--camera): a usage error, not bad data in the file.
  if (!requested.empty()) {
    if (std::find(cameras.begin(), cameras.end(), requested) != cameras.end()) return requested;
    throw config::UsageError("--camera " + requested + ": calibration file '" + path +
                             "' has no camera '" + requested +
                             "'; its cameras: " + (names.empty() ? std::string("(none)") : names));
  }
  if (cameras.size() <= 1) return "cam0";
  throw config::UsageError("calibration file '" + path + "' is a camchain of " +
                           std::to_string(cameras.size()) + " cameras (" + names +
                           "); choose the one the frames come from with --camera (e.g. "
                           "--camera " +
                           cameras[1] + ")");
}

CameraCalibration LoadKalibr(const std::string& path, const std::string& requested_camera) {
  const YAML::Node root = LoadYaml(path);
  const std::string camera_key = KalibrCameraKey(root, path, requested_camera);
  const YAML::Node cam = Require(root, camera_key, path, camera_key);
  auto field = [&camera_key](const std::string& key) { return camera_key + "." + key; };
  ParsedCalibration parsed;
  parsed.name = camera_key;
  const std::string camera_model =
      As<std::string>(Require(cam, "camera_model", path, field("camera_model")), path,
                      field("camera_model"), "a string");
  if (camera_model != "pinhole") {
    Fail(path, field("camera_model"),
         "unsupported projection '" + camera_model + "'; only pinhole is supported");
  }
  const auto intrinsics =
      As<std::vector<double>>(Require(cam, "intrinsics", path, field("intrinsics")), path,
                              field("intrinsics"), "a list [fu, fv, pu, pv]");
  if (intrinsics.size() != 4) {
    Fail(path, field("intrinsics"),
         "expected 4 values [fu, fv, pu, pv], got " + std::to_string(intrinsics.size()));
  }
  parsed.intrinsics = Eigen::Vector4d(intrinsics.data());
  const auto resolution =
      As<std::vector<int>>(Require(cam, "resolution", path, field("resolution")), path,
                           field("resolution"), "a list [width, height]");
  if (resolution.size() != 2) {
    Fail(path, field("resolution"),
         "expected 2 values [width, height], got " + std::to_string(resolution.size()));
  }
  parsed.width = resolution[0];
  parsed.height = resolution[1];
  const std::string model =
      As<std::string>(Require(cam, "distortion_model", path, field("distortion_model")), path,
                      field("distortion_model"), "a string");
  if (model == "radtan" || model == "equidistant") {
    parsed.model = model;
  } else if (model == "none") {
    parsed.model = "pinhole";
  } else {
    Fail(path, field("distortion_model"),
         "unsupported model '" + model + "'; expected radtan, equidistant or none");
  }
  const auto coeffs =
      As<std::vector<double>>(Require(cam, "distortion_coeffs", path, field("distortion_coeffs")),
                              path, field("distortion_coeffs"), "a list of numbers");
  parsed.distortion =
      Eigen::Map<const Eigen::VectorXd>(coeffs.data(), static_cast<Eigen::Index>(coeffs.size()));
  if (cam["T_cam_imu"]) {
    const auto rows = As<std::vector<std::vector<double>>>(cam["T_cam_imu"], path,
                                                           field("T_cam_imu"), "a 4x4 list");
    FlatMatrix m{
        static_cast<int>(rows.size()), rows.empty() ? 0 : static_cast<int>(rows[0].size()), {}};
    for (const auto& row : rows) {
      if (static_cast<int>(row.size()) != m.cols)
        Fail(path, field("T_cam_imu"), "rows have different lengths");
      m.data.insert(m.data.end(), row.begin(), row.end());
    }
    // T_cam_imu maps IMU (= body) points into the camera: T_CB. We keep T_BC.
    parsed.T_BC = TransformFromMatrix(m, path, field("T_cam_imu")).inverse();
  }
  return Build(parsed, path);
}

void SaveKalibr(const CameraCalibration& calib, const std::string& path) {
  const CameraModel& cam = *calib.camera;
  const Eigen::Vector4d k = cam.intrinsics();
  const Eigen::VectorXd d = cam.distortion();
  const Eigen::Matrix4d T_CB = calib.T_BC.inverse().matrix();
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap << YAML::Key << "cam0" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "T_cam_imu" << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < 4; ++r) {
    out << YAML::Flow << std::vector<double>{T_CB(r, 0), T_CB(r, 1), T_CB(r, 2), T_CB(r, 3)};
  }
  out << YAML::EndSeq;
  out << YAML::Key << "camera_model" << YAML::Value << "pinhole";
  out << YAML::Key << "intrinsics" << YAML::Value << YAML::Flow
      << std::vector<double>{k[0], k[1], k[2], k[3]};
  out << YAML::Key << "distortion_model" << YAML::Value
      << (cam.model_name() == "pinhole" ? std::string("none") : cam.model_name());
  out << YAML::Key << "distortion_coeffs" << YAML::Value << YAML::Flow
      << std::vector<double>(d.data(), d.data() + d.size());
  out << YAML::Key << "resolution" << YAML::Value << YAML::Flow
      << std::vector<int>{cam.width(), cam.height()};
  out << YAML::EndMap << YAML::EndMap;
  WriteYamlFile(out, path);
}

}  // namespace

CalibrationFormat ParseCalibrationFormat(const std::string& name) {
  if (name == "opencv") return CalibrationFormat::kOpenCv;
  if (name == "ros") return CalibrationFormat::kRos;
  if (name == "kalibr") return CalibrationFormat::kKalibr;
  throw std::invalid_argument("calibration format '" + name +
                              "' is unknown; use opencv, ros or kalibr");
}

std::string CalibrationFormatName(CalibrationFormat format) {
  switch (format) {
    case CalibrationFormat::kOpenCv:
      return "opencv";
    case CalibrationFormat::kRos:
      return "ros";
    case CalibrationFormat::kKalibr:
      return "kalibr";
  }
  return "unknown";
}

CalibrationFormat DetectCalibrationFormat(const std::string& path) {
  config::RequireRegularFileIfPresent(path, "calibration file");
  std::ifstream file(path);
  if (!file) Fail(path, "(file)", "cannot be opened; check the path");
  std::string first_line;
  std::getline(file, first_line);
  // cv::FileStorage YAML starts with "%YAML:1.0", which yaml-cpp rejects; its XML with "<?xml".
  if (first_line.rfind("%YAML:1.", 0) == 0 || first_line.rfind("<?xml", 0) == 0)
    return CalibrationFormat::kOpenCv;
  const YAML::Node root = LoadYaml(path);
  if (root.IsMap() && root["cam0"]) return CalibrationFormat::kKalibr;
  if (root.IsMap() && root["camera_matrix"] && root["camera_matrix"].IsMap() &&
      root["camera_matrix"]["data"]) {
    return CalibrationFormat::kRos;
  }
  Fail(path, "(format)",
       "not a known calibration format: expected OpenCV FileStorage (%YAML:1.0 header), ROS "
       "camera_info (camera_matrix with data) or a Kalibr camchain (cam0)");
}

CameraCalibration LoadCameraCalibration(const std::string& path, const std::string& kalibr_camera) {
  switch (DetectCalibrationFormat(path)) {
    case CalibrationFormat::kOpenCv:
      return LoadOpenCv(path);
    case CalibrationFormat::kRos:
      return LoadRos(path);
    case CalibrationFormat::kKalibr:
      return LoadKalibr(path, kalibr_camera);
  }
  Fail(path, "(format)", "unknown format");
}

void SaveCameraCalibration(const CameraCalibration& calib, const std::string& path,
                           CalibrationFormat format) {
  if (!calib.camera)
    throw std::invalid_argument("SaveCameraCalibration('" + path + "'): calibration has no camera");
  switch (format) {
    case CalibrationFormat::kOpenCv:
      return SaveOpenCv(calib, path);
    case CalibrationFormat::kRos:
      return SaveRos(calib, path);
    case CalibrationFormat::kKalibr:
      return SaveKalibr(calib, path);
  }
}

void CheckCalibrationImageSize(const CameraCalibration& calib, int width, int height) {
  if (!calib.camera) throw std::invalid_argument("calibration has no camera model");
  if (calib.camera->width() == width && calib.camera->height() == height) return;
  const std::string source =
      calib.source_path.empty() ? std::string("(built in code)") : "'" + calib.source_path + "'";
  throw std::invalid_argument(
      "calibration " + source + " is for " + std::to_string(calib.camera->width()) + "x" +
      std::to_string(calib.camera->height()) + " images but the images are " +
      std::to_string(width) + "x" + std::to_string(height) +
      ": pass the calibration of this camera, or scale it with CameraModel::Scaled(" +
      std::to_string(width) + ", " + std::to_string(height) + ") if the images were resized");
}

CameraCalibration CalibrationFromRosCameraInfo(const RosCameraInfo& info,
                                               const std::string& source) {
  const FlatMatrix K{3, 3, info.K};
  const FlatMatrix D{1, static_cast<int>(info.D.size()), info.D};
  ParsedCalibration parsed =
      ParseRosCamera(info.width, info.height, K, info.distortion_model, D, source);
  parsed.name = info.name;
  return Build(parsed, source);
}

}  // namespace aperture::perception
