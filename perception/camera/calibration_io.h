#pragma once
// Camera calibration files: load and save a camera model plus its extrinsics in three formats.
//
//  kOpenCv  cv::FileStorage YAML as written by OpenCV's calibration sample ("%YAML:1.0" header;
//           image_width, image_height, camera_matrix, distortion_coefficients as !!opencv-matrix).
//           We add distortion_model: radtan|equidistant|pinhole (absent on load = radtan) and the
//           optional keys camera_name and T_BC (4x4).
//  kRos     ROS camera_info YAML (camera_calibration_parsers): image_width, image_height,
//           camera_name, camera_matrix{rows,cols,data}, distortion_model plumb_bob|equidistant,
//           distortion_coefficients{rows,cols,data} (+ rectification/projection on save, optional
//           T_BC on load). A pinhole camera is saved as plumb_bob with zero coefficients and loads
//           back as a radtan camera with zero distortion (same projection).
//  kKalibr  Kalibr camchain YAML, camera cam0: camera_model pinhole, intrinsics [fu fv pu pv],
//           distortion_model radtan|equidistant|none, distortion_coeffs, resolution [w h],
//           T_cam_imu (4x4). The IMU frame is B, so T_BC = T_cam_imu^-1.
//
// Every load error (missing or unparsable file, missing key, fx <= 0, wrong coefficient count,
// rows*cols not matching the data, unknown model) throws std::invalid_argument whose message names
// the file and the field.
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

struct CameraCalibration {
  std::shared_ptr<const CameraModel> camera;
  // Camera-to-body extrinsics: p_B = T_BC * p_C. Identity when the file has none.
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  std::string name;         // camera name (empty when the format or file has none)
  std::string source_path;  // file it was loaded from; empty when built in code
};

enum class CalibrationFormat { kOpenCv, kRos, kKalibr };

// "opencv" | "ros" | "kalibr"; throws std::invalid_argument naming the value otherwise.
CalibrationFormat ParseCalibrationFormat(const std::string& name);
std::string CalibrationFormatName(CalibrationFormat format);

// Detects the format from the file content: a "%YAML:1.x" header (or XML) is OpenCV
// FileStorage, a top-level cam0 key is Kalibr, a camera_matrix map with data is ROS.
CalibrationFormat DetectCalibrationFormat(const std::string& path);

// Loads any of the three formats (detected). For Kalibr, kalibr_camera selects the camera key
// (cam0, cam1, ...); empty: the file's only camera, and std::invalid_argument listing the cameras
// when it holds several (`aperture run --camera camN` chooses).
CameraCalibration LoadCameraCalibration(const std::string& path,
                                        const std::string& kalibr_camera = "");

// Writes calib in the given format (doubles with 17 significant digits: exact round trip).
// Throws std::invalid_argument when calib has no camera and std::runtime_error when the file
// cannot be written.
void SaveCameraCalibration(const CameraCalibration& calib, const std::string& path,
                           CalibrationFormat format);

// Throws std::invalid_argument naming the calibration file and both sizes when the calibration
// was made for another image size than width x height.
void CheckCalibrationImageSize(const CameraCalibration& calib, int width, int height);

// The fields of a ROS sensor_msgs/CameraInfo message that define the camera (a bag's camera_info
// topic; perception/io/rosbag_source.h reads them): K row-major 3x3, D, distortion_model
// plumb_bob -> radtan, equidistant -> equidistant, "" with no D -> pinhole.
struct RosCameraInfo {
  int width = 0;
  int height = 0;
  std::vector<double> K;
  std::string distortion_model;
  std::vector<double> D;
  std::string name;  // e.g. the message's frame_id
};

// Throws std::invalid_argument naming `source` (e.g. "bag 'x.bag' topic '/cam0/camera_info'")
// and the field, like LoadCameraCalibration does for a file.
CameraCalibration CalibrationFromRosCameraInfo(const RosCameraInfo& info,
                                               const std::string& source);

}  // namespace aperture::perception
