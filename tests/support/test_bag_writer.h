#pragma once
// Writes small ROS1 bags for the tests with the library RosbagSource reads them with (rosbag
// storage): images, IMU samples and a camera_info, each stamped and recorded at the given time.
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "perception/camera/camera_model.h"

namespace aperture::test_support {

class TestBagWriter {
 public:
  explicit TestBagWriter(const std::string& path) : bag_(path, rosbag::bagmode::Write) {}

  // `image` (8-bit, 1 or 3 channels, row-major) as `encoding` (e.g. mono8, bgr8); the bytes are
  // written as they are, so the caller passes RGB data for rgb8. Stamped t_s, recorded at
  // received_t_s (the bag's order; < 0: at t_s).
  void WriteImage(const std::string& topic, double t_s, const cv::Mat& image,
                  const std::string& encoding, double received_t_s = -1.0) {
    sensor_msgs::Image message;
    message.header.stamp = ros::Time(t_s);
    message.header.frame_id = "cam0";
    message.height = image.rows;
    message.width = image.cols;
    message.encoding = encoding;
    message.step = static_cast<uint32_t>(image.cols * image.elemSize());
    const cv::Mat continuous = image.isContinuous() ? image : image.clone();
    message.data.assign(continuous.data, continuous.data + image.total() * image.elemSize());
    bag_.write(topic, received_t_s < 0.0 ? message.header.stamp : ros::Time(received_t_s), message);
  }

  // `image` encoded as `extension` (".png", ".jpg").
  void WriteCompressedImage(const std::string& topic, double t_s, const cv::Mat& image,
                            const std::string& extension) {
    sensor_msgs::CompressedImage message;
    message.header.stamp = ros::Time(t_s);
    message.format = extension.substr(1);
    cv::imencode(extension, image, message.data);
    bag_.write(topic, message.header.stamp, message);
  }

  void WriteImu(const std::string& topic, double t_s, const Eigen::Vector3d& specific_force_B,
                const Eigen::Vector3d& omega_B) {
    sensor_msgs::Imu message;
    message.header.stamp = ros::Time(t_s);
    message.linear_acceleration.x = specific_force_B.x();
    message.linear_acceleration.y = specific_force_B.y();
    message.linear_acceleration.z = specific_force_B.z();
    message.angular_velocity.x = omega_B.x();
    message.angular_velocity.y = omega_B.y();
    message.angular_velocity.z = omega_B.z();
    bag_.write(topic, message.header.stamp, message);
  }

  // The camera as ROS describes it: plumb_bob (radtan), equidistant, or pinhole as plumb_bob with
  // zero coefficients.
  void WriteCameraInfo(const std::string& topic, double t_s,
                       const perception::CameraModel& camera) {
    sensor_msgs::CameraInfo message;
    message.header.stamp = ros::Time(t_s);
    message.header.frame_id = "cam0";
    message.width = camera.width();
    message.height = camera.height();
    const Eigen::Vector4d k = camera.intrinsics();
    message.K = {k[0], 0.0, k[2], 0.0, k[1], k[3], 0.0, 0.0, 1.0};
    const bool equidistant = camera.model_name() == "equidistant";
    message.distortion_model = equidistant ? "equidistant" : "plumb_bob";
    const Eigen::VectorXd d =
        camera.model_name() == "pinhole" ? Eigen::VectorXd::Zero(5) : camera.distortion();
    message.D.assign(d.data(), d.data() + d.size());
    bag_.write(topic, message.header.stamp, message);
  }

 private:
  rosbag::Bag bag_;
};

}  // namespace aperture::test_support
