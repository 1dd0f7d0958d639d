#include "perception/io/rosbag_source.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>

#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

constexpr const char* kImageType = "sensor_msgs/Image";
constexpr const char* kCompressedType = "sensor_msgs/CompressedImage";
constexpr const char* kImuType = "sensor_msgs/Imu";
constexpr const char* kCameraInfoType = "sensor_msgs/CameraInfo";

std::unique_ptr<rosbag::Bag> OpenBag(const std::filesystem::path& path) {
  auto bag = std::make_unique<rosbag::Bag>();
  try {
    bag->open(path.string(), rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot read ROS bag '" + path.string() + "': " + e.what());
  }
  return bag;
}

// topic -> message type of every connection in the bag.
std::map<std::string, std::string> TopicTypes(const rosbag::Bag& bag) {
  std::map<std::string, std::string> types;
  rosbag::View everything(bag);
  for (const rosbag::ConnectionInfo* connection : everything.getConnections()) {
    types[connection->topic] = connection->datatype;
  }
  return types;
}

// The topic's type, checked against `allowed`; std::invalid_argument naming the bag's topics.
std::string RequireTopic(const std::map<std::string, std::string>& types,
                         const std::filesystem::path& path, const std::string& topic,
                         const std::vector<std::string>& allowed, const std::string& flag) {
  std::string listing;
  for (const auto& [name, type] : types)
    listing += (listing.empty() ? "" : ", ") + name + " (" + type + ")";
  std::string expected;
  for (const std::string& type : allowed) expected += (expected.empty() ? "" : " or ") + type;
  if (topic.empty()) {
    throw std::invalid_argument("ROS bag '" + path.string() + "': no " + flag +
                                " given; pass one of its topics: " + listing);
  }
  const auto it = types.find(topic);
  if (it == types.end()) {
    throw std::invalid_argument("ROS bag '" + path.string() + "' has no topic '" + topic + "' (" +
                                flag + "); its topics: " + listing);
  }
  for (const std::string& type : allowed) {
    if (it->second == type) return type;
  }
  throw std::invalid_argument("ROS bag '" + path.string() + "' topic '" + topic + "' carries " +
                              it->second + ", not " + expected + " (" + flag +
                              "); its topics: " + listing);
}

double StampSeconds(const ros::Time& header_stamp, const ros::Time& bag_time) {
  return header_stamp.isZero() ? bag_time.toSec() : header_stamp.toSec();
}

// A sensor_msgs/Image as an 8-bit gray or BGR cv::Mat (a copy). Unknown encodings throw.
cv::Mat ImageFromMessage(const sensor_msgs::Image& message, const std::string& where) {
  const std::string& encoding = message.encoding;
  int channels = 0, conversion = -1;
  if (encoding == "mono8" || encoding == "8UC1") {
    channels = 1;
  } else if (encoding == "bgr8" || encoding == "8UC3") {
    channels = 3;
  } else if (encoding == "rgb8") {
    channels = 3, conversion = cv::COLOR_RGB2BGR;
  } else if (encoding == "bgra8") {
    channels = 4, conversion = cv::COLOR_BGRA2BGR;
  } else if (encoding == "rgba8") {
    channels = 4, conversion = cv::COLOR_RGBA2BGR;
  } else {
    throw std::invalid_argument(where + ": image encoding '" + encoding +
                                "' is not supported; aperture reads mono8, bgr8, rgb8, bgra8, "
                                "rgba8 (8UC1, 8UC3) and sensor_msgs/CompressedImage");
  }
  const size_t row_bytes = size_t(message.width) * channels;
  if (message.step < row_bytes || message.data.size() < size_t(message.step) * message.height) {
    throw std::invalid_argument(where + ": image " + std::to_string(message.width) + "x" +
                                std::to_string(message.height) + " " + encoding + " with step " +
                                std::to_string(message.step) + " holds only " +
                                std::to_string(message.data.size()) + " bytes");
  }
  const cv::Mat view(int(message.height), int(message.width), CV_8UC(channels),
                     const_cast<uint8_t*>(message.data.data()), message.step);
  cv::Mat image;
  if (conversion >= 0) {
    cv::cvtColor(view, image, conversion);
  } else {
    image = view.clone();
  }
  return image;
}

}  // namespace

struct RosbagSource::Reader {
  std::unique_ptr<rosbag::Bag> bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator next;
};

RosbagSource::RosbagSource(const std::filesystem::path& path, const FrameSourceOptions& options)
    : path_(path), options_(options), reader_(std::make_unique<Reader>()) {
  CheckFrameSourceOptions(options);
  reader_->bag = OpenBag(path);
  const std::map<std::string, std::string> types = TopicTypes(*reader_->bag);
  image_type_ = RequireTopic(types, path, options.image_topic, {kImageType, kCompressedType},
                             "--image-topic");
  std::vector<std::string> topics{options.image_topic};
  if (!options.imu_topic.empty()) {
    RequireTopic(types, path, options.imu_topic, {kImuType}, "--imu-topic");
    topics.push_back(options.imu_topic);
  }
  image_count_ = rosbag::View(*reader_->bag, rosbag::TopicQuery(options.image_topic)).size();
  if (!options.imu_topic.empty()) {
    imu_count_ = rosbag::View(*reader_->bag, rosbag::TopicQuery(options.imu_topic)).size();
  }
  // One view over both topics: messages in bag (receive) order, IMU samples between frames.
  reader_->view = std::make_unique<rosbag::View>(*reader_->bag, rosbag::TopicQuery(topics));
  reader_->next = reader_->view->begin();
}

RosbagSource::~RosbagSource() = default;

std::optional<Frame> RosbagSource::Next() {
  for (; reader_->next != reader_->view->end(); ++reader_->next) {
    const rosbag::MessageInstance& message = *reader_->next;
    if (message.getTopic() == options_.imu_topic) {
      const sensor_msgs::Imu::ConstPtr imu = message.instantiate<sensor_msgs::Imu>();
      ImuSample sample;
      sample.t_s = StampSeconds(imu->header.stamp, message.getTime());
      sample.specific_force_B << imu->linear_acceleration.x, imu->linear_acceleration.y,
          imu->linear_acceleration.z;
      sample.omega_B << imu->angular_velocity.x, imu->angular_velocity.y, imu->angular_velocity.z;
      imu_.push_back(sample);
      continue;
    }
    const int index = next_index_++;
    const std::string where = "ROS bag '" + path_.string() + "' topic '" + options_.image_topic +
                              "' message " + std::to_string(index);
    Frame frame;
    frame.index = index;
    frame.camera_id = options_.camera_id;
    if (image_type_ == kImageType) {
      const sensor_msgs::Image::ConstPtr image = message.instantiate<sensor_msgs::Image>();
      frame.t_s = StampSeconds(image->header.stamp, message.getTime());
      frame.image = ImageFromMessage(*image, where);  // an unknown encoding is never skipped
    } else {
      const sensor_msgs::CompressedImage::ConstPtr image =
          message.instantiate<sensor_msgs::CompressedImage>();
      frame.t_s = StampSeconds(image->header.stamp, message.getTime());
      frame.image = cv::imdecode(image->data, cv::IMREAD_UNCHANGED);
      if (frame.image.empty() || frame.image.depth() != CV_8U) {
        const std::string reason = "format '" + image->format + "' could not be decoded to 8 bits";
        if (!options_.skip_bad_frames) throw std::runtime_error(where + ": " + reason);
        RecordSkip("message " + std::to_string(index), reason);
        continue;
      }
    }
    if (width_ == 0) width_ = frame.image.cols, height_ = frame.image.rows;
    if (frame.image.cols != width_ || frame.image.rows != height_) {
      const std::string reason = "image is " + std::to_string(frame.image.cols) + "x" +
                                 std::to_string(frame.image.rows) + ", the first frame was " +
                                 std::to_string(width_) + "x" + std::to_string(height_);
      if (!options_.skip_bad_frames) throw std::invalid_argument(where + ": " + reason);
      RecordSkip("message " + std::to_string(index), reason);
      continue;
    }
    if (index > 0 && !(frame.t_s > last_t_s_)) {
      throw std::invalid_argument(where + ": time " + std::to_string(frame.t_s) +
                                  " s does not increase (previous frame " +
                                  std::to_string(last_t_s_) +
                                  " s); aperture reads bags in the "
                                  "order they were recorded: reorder the bag by header stamp");
    }
    last_t_s_ = frame.t_s;
    frame.image = ConvertToColorMode(frame.image, options_.color_mode);
    ++reader_->next;
    return frame;
  }
  return std::nullopt;
}

std::vector<ImuSample> RosbagSource::TakeImuSamples() {
  std::vector<ImuSample> samples;
  samples.swap(imu_);
  return samples;
}

std::string RosbagSource::Describe() const {
  std::string description = "ROS bag '" + path_.string() + "' (" + std::to_string(image_count_) +
                            " " + image_type_ + " on " + options_.image_topic;
  if (!options_.imu_topic.empty()) {
    description += ", " + std::to_string(imu_count_) + " sensor_msgs/Imu on " + options_.imu_topic;
  }
  return description + ")";
}

CameraCalibration LoadCameraInfoFromBag(const std::filesystem::path& path,
                                        const std::string& topic) {
  const std::unique_ptr<rosbag::Bag> bag = OpenBag(path);
  RequireTopic(TopicTypes(*bag), path, topic, {kCameraInfoType}, "--camera-info-topic");
  rosbag::View view(*bag, rosbag::TopicQuery(topic));
  const std::string source = "ROS bag '" + path.string() + "' topic '" + topic + "'";
  for (const rosbag::MessageInstance& message : view) {
    const sensor_msgs::CameraInfo::ConstPtr info = message.instantiate<sensor_msgs::CameraInfo>();
    RosCameraInfo fields;
    fields.width = static_cast<int>(info->width);
    fields.height = static_cast<int>(info->height);
    fields.K.assign(info->K.begin(), info->K.end());
    fields.distortion_model = info->distortion_model;
    fields.D = info->D;
    fields.name = info->header.frame_id;
    return CalibrationFromRosCameraInfo(fields, source);
  }
  throw std::invalid_argument(source +
                              " holds no message; record the camera_info topic or "
                              "pass --calib FILE");
}

}  // namespace aperture::perception
