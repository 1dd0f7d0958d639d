#pragma once
// Sensor data that crosses the sensor / autonomy boundary: the same types come from a real camera
// and IMU, from a recorded sequence, or from the simulator. Units SI, time in seconds on the
// clock of the data source (the simulator clock in SITL).
#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace aperture::perception {

struct ImuSample {
  double t_s = 0.0;
  Eigen::Vector3d specific_force_B = Eigen::Vector3d::Zero();  // accelerometer [m/s^2]
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();           // gyroscope [rad/s]
};

struct Frame {
  double t_s = 0.0;   // mid-exposure timestamp [s]
  int camera_id = 0;  // index into the rig's cameras
  int index = 0;      // running index in its source
  cv::Mat image;      // CV_8UC1 (gray) or CV_8UC3 (BGR)
  // The source's IMU samples since its previous frame, oldest first (FrameSource::TakeImuSamples,
  // filled by RunSource); empty for sources without an IMU.
  std::vector<ImuSample> imu;
};

// Downward range sensor reading along -z_B [m]; valid == false when out of range.
struct RangeReading {
  double t_s = 0.0;
  double range_m = 0.0;
  bool valid = false;
};

}  // namespace aperture::perception
