// Calibration files: reading files as the tools write them, save/load round trips in every
// format, format detection, and errors that name the file and the field.
#include "perception/camera/calibration_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "perception/camera/camera_factory.h"
#include "tests/perception/temp_directory.h"

namespace aperture::perception {
namespace {

const std::string kDataDir = std::string(APERTURE_TEST_DATA_DIR) + "/calibration/";

TEST(CalibrationIoTest, LoadsOpenCvCalibrationSampleOutput) {
  const std::string path = kDataDir + "opencv_sample.yaml";
  EXPECT_EQ(DetectCalibrationFormat(path), CalibrationFormat::kOpenCv);
  const CameraCalibration calib = LoadCameraCalibration(path);
  ASSERT_TRUE(calib.camera);
  EXPECT_EQ(calib.camera->model_name(), "radtan");  // no distortion_model key: plumb bob
  EXPECT_EQ(calib.camera->width(), 640);
  EXPECT_EQ(calib.camera->height(), 480);
  EXPECT_EQ(calib.camera->intrinsics(),
            Eigen::Vector4d(5.3591573396163199e+02, 5.3598120025513981e+02, 3.4228315473308373e+02,
                            2.3557082909788173e+02));
  ASSERT_EQ(calib.camera->distortion().size(), 5);
  EXPECT_EQ(calib.camera->distortion()[4], 2.3839153080878486e-01);
  EXPECT_TRUE(calib.T_BC.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(calib.source_path, path);
}

TEST(CalibrationIoTest, LoadsRosCameraInfo) {
  const std::string path = kDataDir + "ros_camera_info.yaml";
  EXPECT_EQ(DetectCalibrationFormat(path), CalibrationFormat::kRos);
  const CameraCalibration calib = LoadCameraCalibration(path);
  EXPECT_EQ(calib.camera->model_name(), "equidistant");
  EXPECT_EQ(calib.name, "t265_fisheye1");
  EXPECT_EQ(calib.camera->width(), 848);
  EXPECT_EQ(calib.camera->intrinsics(), Eigen::Vector4d(286.1807, 286.3934, 416.9417, 403.6245));
  EXPECT_EQ(calib.camera->distortion(), Eigen::Vector4d(-0.0102, 0.0471, -0.0444, 0.0083));
}

TEST(CalibrationIoTest, LoadsKalibrCamchainWithInverseExtrinsics) {
  const std::string path = kDataDir + "euroc_cam0_kalibr.yaml";
  EXPECT_EQ(DetectCalibrationFormat(path), CalibrationFormat::kKalibr);
  // Two cameras: which one the frames come from is the user's choice, never silently cam0.
  try {
    LoadCameraCalibration(path);
    FAIL() << "a two-camera camchain needs a camera choice";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 cameras (cam0, cam1)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--camera cam1"), std::string::npos) << e.what();
  }
  const CameraCalibration cam0 = LoadCameraCalibration(path, "cam0");
  EXPECT_EQ(cam0.camera->model_name(), "radtan");
  EXPECT_EQ(cam0.camera->width(), 752);
  EXPECT_EQ(cam0.camera->intrinsics(), Eigen::Vector4d(458.654, 457.296, 367.215, 248.375));
  // EuRoC's sensor.yaml T_BS of cam0 (camera to body). The file stores its inverse to 1e-16 but
  // the published rotation is orthonormal to ~1e-10 only, hence 1e-9.
  Eigen::Matrix4d T_BS;
  T_BS << 0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,  //
      0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,          //
      -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,      //
      0.0, 0.0, 0.0, 1.0;
  EXPECT_LT((cam0.T_BC.matrix() - T_BS).cwiseAbs().maxCoeff(), 1e-9);
  const CameraCalibration cam1 = LoadCameraCalibration(path, "cam1");
  EXPECT_EQ(cam1.camera->intrinsics()[0], 457.587);
  EXPECT_EQ(cam1.name, "cam1");
}

class CalibrationRoundTripTest
    : public ::testing::TestWithParam<std::tuple<CalibrationFormat, std::string>> {};

// Save then load gives the same calibration to 1e-12 (17 significant digits are written; the
// Kalibr extrinsics are inverted twice, which costs a few ulp).
TEST_P(CalibrationRoundTripTest, SaveThenLoadIsIdentity) {
  const auto [format, model] = GetParam();
  Eigen::VectorXd distortion;
  if (model == "radtan4") distortion = Eigen::Vector4d(-0.283408, 0.0739590, 1.9359e-4, 1.7618e-5);
  if (model == "radtan") {
    distortion.resize(5);
    distortion << -0.2663726090966068, -0.0385888989223, 1.78319470428e-3, -2.81221e-4, 0.2383915;
  }
  if (model == "equidistant") distortion = Eigen::Vector4d(-0.0102, 0.0471, -0.0444, 0.0083);
  const std::string model_name = model == "radtan4" ? "radtan" : model;
  CameraCalibration calib;
  calib.camera = CreateCameraModel(
      model_name, 752, 480, Eigen::Vector4d(458.654321, 457.2961, 367.215, 248.3751), distortion);
  calib.T_BC = Eigen::Translation3d(0.1, -0.02, 0.035) *
               Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  calib.name = "front_left";
  const test_support::TempDirectory temp;
  const std::string path = (temp.path() / ("round_trip_" + model + ".yaml")).string();
  SaveCameraCalibration(calib, path, format);
  EXPECT_EQ(DetectCalibrationFormat(path), format);
  const CameraCalibration loaded = LoadCameraCalibration(path);
  ASSERT_TRUE(loaded.camera);
  EXPECT_EQ(loaded.camera->width(), 752);
  EXPECT_EQ(loaded.camera->height(), 480);
  EXPECT_LT((loaded.camera->intrinsics() - calib.camera->intrinsics()).cwiseAbs().maxCoeff(),
            1e-12);
  if (format == CalibrationFormat::kRos && model == "pinhole") {
    // ROS has no distortion-free model: plumb_bob with zero coefficients.
    EXPECT_EQ(loaded.camera->model_name(), "radtan");
    EXPECT_EQ(loaded.camera->distortion(), Eigen::VectorXd::Zero(5));
  } else {
    EXPECT_EQ(loaded.camera->model_name(), calib.camera->model_name());
    ASSERT_EQ(loaded.camera->distortion().size(), distortion.size());
    if (distortion.size() > 0) {
      EXPECT_LT((loaded.camera->distortion() - distortion).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
  EXPECT_LT((loaded.T_BC.matrix() - calib.T_BC.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  if (format != CalibrationFormat::kKalibr) {
    EXPECT_EQ(loaded.name, "front_left");
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, CalibrationRoundTripTest,
    ::testing::Combine(::testing::Values(CalibrationFormat::kOpenCv, CalibrationFormat::kRos,
                                         CalibrationFormat::kKalibr),
                       ::testing::Values("pinhole", "radtan4", "radtan", "equidistant")),
    [](const auto& info) {
      return CalibrationFormatName(std::get<0>(info.param)) + "_" + std::get<1>(info.param);
    });

struct InvalidFileCase {
  std::string label;
  std::string content;
  std::string field;  // must appear in the message, together with the file name
};

std::ostream& operator<<(std::ostream& os, const InvalidFileCase& c) { return os << c.label; }

class InvalidCalibrationFileTest : public ::testing::TestWithParam<InvalidFileCase> {};

TEST_P(InvalidCalibrationFileTest, ErrorNamesFileAndField) {
  const test_support::TempDirectory temp;
  const std::string path = (temp.path() / ("bad_" + GetParam().label + ".yaml")).string();
  std::ofstream(path) << GetParam().content;
  try {
    LoadCameraCalibration(path);
    FAIL() << "no error for " << GetParam().label;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().field), std::string::npos) << message;
  }
}

const std::string kOpenCvHeader = "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n";
const std::string kOpenCvK =
    "camera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n"
    "  data: [500., 0., 320., 0., 500., 240., 0., 0., 1.]\n";
std::string OpenCvD(int n) {
  std::string data = "[";
  for (int i = 0; i < n; ++i) data += (i ? ", " : "") + std::string("0.01");
  return "distortion_coefficients: !!opencv-matrix\n  rows: " + std::to_string(n) +
         "\n  cols: 1\n  dt: d\n  data: " + data + "]\n";
}
const std::string kRosK =
    "image_width: 640\nimage_height: 480\ncamera_name: c\n"
    "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n";
const std::string kRosD =
    "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [0.1, 0.01, 0, 0, 0]\n";
std::string Kalibr(const std::string& camera_model, const std::string& intrinsics,
                   const std::string& distortion_model, const std::string& coeffs,
                   const std::string& resolution, const std::string& T = "") {
  return "cam0:\n  camera_model: " + camera_model + "\n  intrinsics: " + intrinsics +
         "\n  distortion_model: " + distortion_model + "\n  distortion_coeffs: " + coeffs +
         "\n  resolution: " + resolution + "\n" + T;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, InvalidCalibrationFileTest,
    ::testing::Values(
        InvalidFileCase{"opencv_missing_width",
                        "%YAML:1.0\n---\nimage_height: 480\n" + kOpenCvK + OpenCvD(5),
                        "image_width"},
        InvalidFileCase{"opencv_zero_fx",
                        kOpenCvHeader +
                            "camera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n"
                            "  data: [0., 0., 320., 0., 500., 240., 0., 0., 1.]\n" +
                            OpenCvD(5),
                        "fx"},
        InvalidFileCase{"opencv_three_coefficients", kOpenCvHeader + kOpenCvK + OpenCvD(3),
                        "distortion"},
        InvalidFileCase{"opencv_rational_model", kOpenCvHeader + kOpenCvK + OpenCvD(8),
                        "distortion_coefficients"},
        InvalidFileCase{"opencv_equidistant_five",
                        kOpenCvHeader + kOpenCvK + OpenCvD(5) + "distortion_model: equidistant\n",
                        "distortion"},
        InvalidFileCase{"opencv_unknown_model",
                        kOpenCvHeader + kOpenCvK + OpenCvD(5) + "distortion_model: fov\n",
                        "distortion_model"},
        InvalidFileCase{"opencv_missing_distortion", kOpenCvHeader + kOpenCvK,
                        "distortion_coefficients"},
        InvalidFileCase{"opencv_rows_cols_mismatch",
                        kOpenCvHeader +
                            "camera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n"
                            "  data: [500., 0., 320., 0., 500., 240., 0., 0.]\n" +
                            OpenCvD(5),
                        "camera_matrix"},
        InvalidFileCase{"ros_missing_distortion_model", kRosK + kRosD, "distortion_model"},
        InvalidFileCase{"ros_unknown_model",
                        kRosK + "distortion_model: rational_polynomial\n" + kRosD,
                        "distortion_model"},
        InvalidFileCase{"ros_negative_fy",
                        "image_width: 640\nimage_height: 480\ncamera_matrix:\n  rows: 3\n  cols: "
                        "3\n  data: [500, 0, 320, 0, -500, 240, 0, 0, 1]\n"
                        "distortion_model: plumb_bob\n" +
                            kRosD,
                        "fy"},
        InvalidFileCase{"ros_rows_cols_mismatch",
                        kRosK + "distortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n"
                                "  cols: 5\n  data: [0.1, 0.01, 0, 0]\n",
                        "distortion_coefficients"},
        InvalidFileCase{"ros_missing_height",
                        "image_width: 640\ncamera_matrix:\n  rows: 3\n  cols: 3\n"
                        "  data: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n"
                        "distortion_model: plumb_bob\n" +
                            kRosD,
                        "image_height"},
        InvalidFileCase{"kalibr_missing_intrinsics",
                        "cam0:\n  camera_model: pinhole\n  distortion_model: radtan\n"
                        "  distortion_coeffs: [0, 0, 0, 0]\n  resolution: [640, 480]\n",
                        "cam0.intrinsics"},
        InvalidFileCase{
            "kalibr_three_intrinsics",
            Kalibr("pinhole", "[500, 500, 320]", "radtan", "[0, 0, 0, 0]", "[640, 480]"),
            "cam0.intrinsics"},
        InvalidFileCase{
            "kalibr_omni",
            Kalibr("omni", "[500, 500, 320, 240]", "radtan", "[0, 0, 0, 0]", "[640, 480]"),
            "cam0.camera_model"},
        InvalidFileCase{
            "kalibr_three_coefficients",
            Kalibr("pinhole", "[500, 500, 320, 240]", "radtan", "[0, 0, 0]", "[640, 480]"),
            "distortion"},
        InvalidFileCase{
            "kalibr_bad_resolution",
            Kalibr("pinhole", "[500, 500, 320, 240]", "equidistant", "[0, 0, 0, 0]", "[640]"),
            "cam0.resolution"},
        InvalidFileCase{
            "kalibr_scaled_rotation",
            Kalibr("pinhole", "[500, 500, 320, 240]", "radtan", "[0, 0, 0, 0]", "[640, 480]",
                   "  T_cam_imu:\n  - [2, 0, 0, 0]\n  - [0, 1, 0, 0]\n"
                   "  - [0, 0, 1, 0]\n  - [0, 0, 0, 1]\n"),
            "cam0.T_cam_imu"},
        InvalidFileCase{"not_yaml", "image_width: [640\n", "(file)"},
        // Found by fuzz/calibration_file_fuzzer.cc: was an escaping cv::Exception (isMap()).
        InvalidFileCase{"opencv_top_level_sequence", "%YAML:1.0\n- image_width: 640\n",
                        "top level must be a map"},
        // Found by fuzz/calibration_file_fuzzer.cc: OpenCV's parser threw std::length_error
        // (basic_string::_M_create) on the empty key before '['.
        InvalidFileCase{"opencv_empty_key_before_bracket", "%YAML:1.0\nm:\n   rows: 3\n   :[a\n",
                        "not a valid OpenCV FileStorage file"},
        // Found by fuzz/calibration_file_fuzzer.cc: OpenCV's base64 reader looped forever.
        InvalidFileCase{
            "opencv_malformed_base64",
            "%YAML:1.0\n"
            "---\n"
            "calibration_time: \"Sat 21 Nov \xaf"
            "2026 10:00:00 UTC\"\n"
            "nframes:\xe0"
            "\xce"
            "3\n"
            "image_width: 640\n"
            "image_height: 480\n"
            "\xa0"
            "\x90"
            "ard_wflags: 0\n"
            "camera_matrix: !!opencv-matrix\n"
            "   rows: 3\n"
            "   cols: 3\n"
            "   dt: !!binary : [ 5.3591573396163199e+02, 0., 3.4228315473308373e+02, 0.,\n"
            "       5.3598120025513981e+02, 2.3557082909788173e+02, 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n"
            "   rows:*a 5\n"
            "   cols: 1\n"
            "   dt: d\n"
            "   data: [ -2.6637260909660682e-01, -3.7831947042852964e-03, "
            "-2.8122100441115472e-04,\n"
            "       258391.33080878486e-01 ]\n"
            "avg_reprojection_error: 3.9259098975581364e-01\n",
            "base64 (!!binary) data is not supported"},
        InvalidFileCase{"unknown_format", "foo: 1\n", "(format)"}),
    [](const auto& info) { return info.param.label; });

TEST(CalibrationIoTest, MissingFileNamesThePath) {
  const test_support::TempDirectory temp;
  const std::string path = (temp.path() / "does_not_exist.yaml").string();
  try {
    LoadCameraCalibration(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(CalibrationIoTest, ImageSizeCheckNamesFileAndBothSizes) {
  const CameraCalibration calib =
      LoadCameraCalibration(kDataDir + "euroc_cam0_kalibr.yaml", "cam0");
  EXPECT_NO_THROW(CheckCalibrationImageSize(calib, 752, 480));
  try {
    CheckCalibrationImageSize(calib, 640, 480);
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("euroc_cam0_kalibr.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("752x480"), std::string::npos) << message;
    EXPECT_NE(message.find("640x480"), std::string::npos) << message;
    EXPECT_NE(message.find("Scaled"), std::string::npos) << message;
  }
}

TEST(CalibrationIoTest, FormatNamesParse) {
  for (auto format :
       {CalibrationFormat::kOpenCv, CalibrationFormat::kRos, CalibrationFormat::kKalibr})
    EXPECT_EQ(ParseCalibrationFormat(CalibrationFormatName(format)), format);
  EXPECT_THROW(ParseCalibrationFormat("matlab"), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
