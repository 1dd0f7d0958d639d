// Intrinsic calibration: pattern-spec parsing, recovery of known intrinsics from synthetic views
// rendered with our camera models, and calibration of real photos of a circle grid (ViSP data).
#include "perception/camera/camera_calibrator.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

#include "perception/camera/calibration_io.h"
#include "perception/camera/camera_factory.h"
#include "tests/perception/temp_directory.h"

namespace aperture::perception {
namespace {

// ------------------------------------------------------------------ synthetic views ---------

struct BoardView {
  double ax_deg, ay_deg, az_deg;  // board orientation (applied z, then y, then x)
  double tx_m, ty_m, distance_m;  // position of the board centre in C
};

// Target-to-camera pose of a view: the board centre lands at (tx, ty, distance).
Eigen::Isometry3d ViewPose(const BoardView& view, const PatternSpec& pattern) {
  const double deg = M_PI / 180.0;
  const Eigen::Vector3d centre_T((pattern.cols - 1) * pattern.spacing_m / 2.0,
                                 (pattern.rows - 1) * pattern.spacing_m / 2.0, 0.0);
  const Eigen::Matrix3d R_CT = (Eigen::AngleAxisd(view.ax_deg * deg, Eigen::Vector3d::UnitX()) *
                                Eigen::AngleAxisd(view.ay_deg * deg, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(view.az_deg * deg, Eigen::Vector3d::UnitZ()))
                                   .toRotationMatrix();
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.linear() = R_CT;
  T_CT.translation() = Eigen::Vector3d(view.tx_m, view.ty_m, view.distance_m) - R_CT * centre_T;
  return T_CT;
}

// Renders a chessboard (inner corners at the PatternObjectPoints, one white square of margin,
// grey background) by casting the ray of every pixel through `camera`. Edges are smoothed with
// a product of clamped sines, symmetric about every corner, so the saddle points (the corners)
// sit exactly at the projected object points.
cv::Mat RenderChessboard(const CameraModel& camera, const PatternSpec& pattern,
                         const Eigen::Isometry3d& T_CT) {
  const Eigen::Isometry3d T_TC = T_CT.inverse();
  const double s = pattern.spacing_m;
  cv::Mat image(camera.height(), camera.width(), CV_8UC1);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const Eigen::Vector3d d_T = T_TC.linear() * camera.Unproject(Eigen::Vector2d(u, v));
      const Eigen::Vector3d o_T = T_TC.translation();
      double intensity = 128.0;
      const double lambda = -o_T.z() / d_T.z();
      if (lambda > 0.0) {
        const Eigen::Vector3d p_T = o_T + lambda * d_T;
        const double x = p_T.x() / s, y = p_T.y() / s;  // in squares, corner 0 at the origin
        if (x > -2.0 && y > -2.0 && x < pattern.cols + 1.0 && y < pattern.rows + 1.0) {
          intensity = 255.0;
          if (x > -1.0 && y > -1.0 && x < pattern.cols && y < pattern.rows) {
            // Ramp half-width 1/(10 pi) square ~ 1.3 px for 40 px squares.
            const double a = std::clamp(10.0 * std::sin(M_PI * x), -1.0, 1.0);
            const double b = std::clamp(10.0 * std::sin(M_PI * y), -1.0, 1.0);
            intensity = 127.5 + 127.5 * a * b;
          }
        }
      }
      image.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(intensity);
    }
  }
  return image;
}

struct SyntheticCase {
  std::string label;
  std::string model;  // camera model that renders the views
  std::vector<double> intrinsics;
  std::vector<double> distortion;
  CalibrationModel calibration_model;
  double distance_scale;  // fisheye views are taken closer
};

std::ostream& operator<<(std::ostream& os, const SyntheticCase& c) { return os << c.label; }

class SyntheticCalibrationTest : public ::testing::TestWithParam<SyntheticCase> {};

TEST_P(SyntheticCalibrationTest, RecoversTheRenderingCamera) {
  const SyntheticCase& c = GetParam();
  const Eigen::VectorXd k_true = Eigen::Map<const Eigen::VectorXd>(c.intrinsics.data(), 4);
  const Eigen::VectorXd d_true =
      Eigen::Map<const Eigen::VectorXd>(c.distortion.data(), c.distortion.size());
  const auto truth = CreateCameraModel(c.model, 640, 480, k_true, d_true);
  const PatternSpec pattern = ParsePatternSpec("chessboard:9x6:0.03");
  const std::vector<BoardView> views = {
      {0, 0, 0, 0, 0, 0.45},          {25, 0, 5, 0.0, 0.06, 0.45},
      {-25, 0, -5, 0.0, -0.06, 0.45}, {0, 25, 10, 0.09, 0, 0.45},
      {0, -25, -10, -0.09, 0, 0.45},  {15, 15, 0, -0.08, -0.06, 0.40},
      {-15, 20, 3, 0.08, 0.06, 0.42}, {20, -15, -3, -0.08, 0.06, 0.42}};
  std::vector<CalibrationImage> images;
  double max_detection_error_px = 0.0;
  for (size_t i = 0; i < views.size(); ++i) {
    BoardView view = views[i];
    view.tx_m *= c.distance_scale;
    view.ty_m *= c.distance_scale;
    view.distance_m *= c.distance_scale;
    const Eigen::Isometry3d T_CT = ViewPose(view, pattern);
    images.push_back({"view" + std::to_string(i), RenderChessboard(*truth, pattern, T_CT)});
    // The detector itself must find the true corners.
    const auto detected = DetectCalibrationPattern(images.back().image, pattern);
    ASSERT_TRUE(detected.has_value()) << images.back().name;
    // A 9x6 board looks the same rotated by 180 deg, so OpenCV may start at either end.
    const std::vector<Eigen::Vector3d> object = PatternObjectPoints(pattern);
    double forward_px = 0.0, reversed_px = 0.0;
    for (size_t k = 0; k < object.size(); ++k) {
      Eigen::Vector2d px;
      ASSERT_TRUE(truth->Project(T_CT * object[k], &px));
      forward_px = std::max(forward_px, (px - (*detected)[k]).norm());
      reversed_px = std::max(reversed_px, (px - (*detected)[object.size() - 1 - k]).norm());
    }
    max_detection_error_px = std::max(max_detection_error_px, std::min(forward_px, reversed_px));
  }
  // cornerSubPix on 8-bit images with ~1.3 px edge ramps: ~0.03 px RMS; the worst of the 432
  // corners (steepest tilt, strongest distortion) measured 0.08-0.10 px, bound 0.2 px.
  EXPECT_LT(max_detection_error_px, 0.2);

  const CameraCalibrationResult result = CalibrateFromImages(images, pattern, c.calibration_model);
  std::cout << c.label << ": max detection error " << max_detection_error_px << " px\n"
            << result << "\n";
  ASSERT_EQ(result.status, CameraCalibrationResult::Status::kOk) << result;
  EXPECT_EQ(result.images_used, static_cast<int>(views.size()));
  EXPECT_LT(result.rms_px, 0.1);  // bounded by the detection error above
  for (const ImageCalibrationResult& image : result.per_image) {
    EXPECT_TRUE(image.found);
    EXPECT_LT(image.rms_px, 0.1) << image.name;
  }
  // With ~0.03 px corner noise over 8 views the intrinsics are determined to a fraction of a
  // pixel; 0.5% of f and 2 px of principal point leave margin for the correlation between them.
  const Eigen::Vector4d k = result.camera->intrinsics();
  EXPECT_NEAR(k[0], k_true[0], 0.005 * k_true[0]);
  EXPECT_NEAR(k[1], k_true[1], 0.005 * k_true[1]);
  EXPECT_NEAR(k[2], k_true[2], 2.0);
  EXPECT_NEAR(k[3], k_true[3], 2.0);
  // The recovered model reproduces the true projection over the calibrated field of view:
  // project rays through a grid of pixels of the central region with both models.
  double max_model_error_px = 0.0;
  for (double u = 80; u <= 560; u += 40) {
    for (double v = 60; v <= 420; v += 40) {
      Eigen::Vector2d px;
      ASSERT_TRUE(result.camera->Project(truth->Unproject(Eigen::Vector2d(u, v)), &px));
      max_model_error_px = std::max(max_model_error_px, (px - Eigen::Vector2d(u, v)).norm());
    }
  }
  std::cout << c.label << ": max model error over the central region " << max_model_error_px
            << " px\n";
  EXPECT_LT(max_model_error_px, 1.0);
}

INSTANTIATE_TEST_SUITE_P(Models, SyntheticCalibrationTest,
                         ::testing::Values(SyntheticCase{"radtan",
                                                         "radtan",
                                                         {520.0, 518.0, 322.5, 236.2},
                                                         {-0.25, 0.08, 0.001, -0.0008},
                                                         CalibrationModel::kRadTan,
                                                         1.0},
                                           SyntheticCase{"fisheye",
                                                         "equidistant",
                                                         {260.0, 261.0, 318.0, 242.0},
                                                         {-0.01, 0.02, -0.005, 0.001},
                                                         CalibrationModel::kFisheye,
                                                         0.55}),
                         [](const auto& info) { return info.param.label; });

// ------------------------------------------------------------------ real photos -------------

// Folder of the ViSP calibration photos: $APERTURE_VISP_CALIBRATION_DIR, or where Debian's
// visp-images-data package installs them.
std::string VispCalibrationDir() {
  if (const char* dir = std::getenv("APERTURE_VISP_CALIBRATION_DIR")) return dir;
  return "/usr/share/visp-images-data/ViSP-images/calibration";
}

TEST(CameraCalibratorTest, CalibratesViSPCircleGridPhotos) {
  const std::string dir = VispCalibrationDir();
  std::vector<CalibrationImage> images;
  for (int i = 1; i <= 4; ++i) {
    const std::string name = "grid36-0" + std::to_string(i) + ".pgm";
    const std::string path = dir + "/" + name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "visp-images-data not installed: " << path;
    images.push_back({name, cv::imread(path, cv::IMREAD_GRAYSCALE)});
  }
  const PatternSpec pattern = ParsePatternSpec("circles:6x6:0.03");
  const test_support::TempDirectory temp;
  std::vector<Eigen::Vector4d> intrinsics;
  for (const CalibrationModel model : {CalibrationModel::kRadTan, CalibrationModel::kFisheye}) {
    const CameraCalibrationResult result = CalibrateFromImages(images, pattern, model);
    std::cout << result << "\n";
    ASSERT_EQ(result.status, CameraCalibrationResult::Status::kOk) << result;
    EXPECT_EQ(result.images_used, 4);
    // Blob centres of real, slightly blurred photos: sub-pixel but not better than ~0.2 px.
    EXPECT_LT(result.rms_px, 0.5);
    for (const ImageCalibrationResult& image : result.per_image) {
      EXPECT_TRUE(image.found) << image.name;
      EXPECT_LT(image.rms_px, 0.5) << image.name;
    }
    intrinsics.push_back(result.camera->intrinsics());
    // Saved and loaded back, the calibration is the same camera.
    CameraCalibration calib;
    calib.camera = result.camera;
    calib.name = "visp_grid36";
    const std::string path =
        (temp.path() / ("visp_grid36_" + result.camera->model_name() + ".yaml")).string();
    SaveCameraCalibration(calib, path, CalibrationFormat::kOpenCv);
    const CameraCalibration loaded = LoadCameraCalibration(path);
    EXPECT_EQ(loaded.camera->model_name(), result.camera->model_name());
    EXPECT_LT((loaded.camera->intrinsics() - result.camera->intrinsics()).cwiseAbs().maxCoeff(),
              1e-12);
    EXPECT_LT((loaded.camera->distortion() - result.camera->distortion()).cwiseAbs().maxCoeff(),
              1e-12);
  }
  // Both models describe the same narrow lens: focal lengths agree to 1%, principal points to
  // 5 px (the difference is absorbed by the different distortion polynomials).
  EXPECT_NEAR(intrinsics[0][0], intrinsics[1][0], 0.01 * intrinsics[0][0]);
  EXPECT_NEAR(intrinsics[0][1], intrinsics[1][1], 0.01 * intrinsics[0][1]);
  EXPECT_NEAR(intrinsics[0][2], intrinsics[1][2], 5.0);
  EXPECT_NEAR(intrinsics[0][3], intrinsics[1][3], 5.0);
}

// ------------------------------------------------------------------ inputs ------------------

TEST(CameraCalibratorTest, ParsesPatternSpecs) {
  const PatternSpec chessboard = ParsePatternSpec("chessboard:9x6:0.025");
  EXPECT_EQ(chessboard.kind, PatternSpec::Kind::kChessboard);
  EXPECT_EQ(chessboard.cols, 9);
  EXPECT_EQ(chessboard.rows, 6);
  EXPECT_EQ(chessboard.spacing_m, 0.025);
  const PatternSpec circles = ParsePatternSpec("circles:6x5:0.03");
  EXPECT_EQ(circles.kind, PatternSpec::Kind::kCircles);
  EXPECT_EQ(circles.rows, 5);
  for (const auto& [spec, part] :
       std::vector<std::pair<std::string, std::string>>{{"chessboard:9x6", "three"},
                                                        {"hexagons:9x6:0.02", "hexagons"},
                                                        {"chessboard:9by6:0.02", "9by6"},
                                                        {"chessboard:9x6x2:0.02", "9x6x2"},
                                                        {"chessboard:1x6:0.02", "too small"},
                                                        {"circles:6x6:-0.03", "-0.03"},
                                                        {"circles:6x6:3cm", "3cm"}}) {
    try {
      ParsePatternSpec(spec);
      ADD_FAILURE() << spec;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(spec), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(ParseCalibrationModel("fisheye"), CalibrationModel::kFisheye);
  EXPECT_THROW(ParseCalibrationModel("omni"), std::invalid_argument);
}

TEST(CameraCalibratorTest, ReportsImagesWithoutTargetAndRejectsMixedSizes) {
  const PatternSpec pattern = ParsePatternSpec("chessboard:9x6:0.03");
  std::vector<CalibrationImage> blank = {{"a.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(90))},
                                         {"b.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(200))},
                                         {"c.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(30))}};
  const CameraCalibrationResult result =
      CalibrateFromImages(blank, pattern, CalibrationModel::kRadTan);
  EXPECT_EQ(result.status, CameraCalibrationResult::Status::kTooFewImages);
  EXPECT_EQ(result.images_used, 0);
  EXPECT_FALSE(result.camera);
  ASSERT_EQ(result.per_image.size(), 3u);
  EXPECT_FALSE(result.per_image[1].found);
  blank.push_back({"small.png", cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))});
  try {
    CalibrateFromImages(blank, pattern, CalibrationModel::kRadTan);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("small.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("320x240"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CalibrateFromImages({}, pattern, CalibrationModel::kRadTan), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
