// RosbagSource on bags the test writes with the same rosbag storage library: every supported
// encoding and CompressedImage against the pixels written, timestamps and indices, IMU samples
// between frames, the camera_info calibration, and each bad input naming what is wrong.
#include "perception/io/rosbag_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "perception/camera/camera_factory.h"
#include "perception/io/open_frame_source.h"
#include "tests/perception/temp_directory.h"
#include "tests/support/message_of.h"
#include "tests/support/test_bag_writer.h"

namespace aperture::perception {
namespace {

using test_support::MessageOf;
using test_support::TestBagWriter;
using ::testing::HasSubstr;

// A BGR test pattern whose channels differ, so a swapped R and B shows.
cv::Mat Pattern(int seed) {
  cv::Mat bgr(24, 32, CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      bgr.at<cv::Vec3b>(y, x) =
          cv::Vec3b(uint8_t(7 * x + seed), uint8_t(5 * y + 2 * seed), uint8_t(x * y + 3 * seed));
    }
  }
  return bgr;
}

FrameSourceOptions BagOptions(const std::string& image_topic, ColorMode mode = ColorMode::kColor,
                              const std::string& imu_topic = "") {
  FrameSourceOptions options;
  options.image_topic = image_topic;
  options.imu_topic = imu_topic;
  options.color_mode = mode;
  return options;
}

void ExpectSameImage(const cv::Mat& a, const cv::Mat& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.type(), b.type());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(RosbagSourceTest, ReadsEveryEncodingAsTheBgrImageWritten) {
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "encodings.bag").string();
  const std::vector<std::string> encodings{"bgr8", "rgb8", "bgra8", "rgba8", "mono8", "8UC3"};
  {
    TestBagWriter bag(path);
    for (size_t i = 0; i < encodings.size(); ++i) {
      const cv::Mat bgr = Pattern(int(i));
      cv::Mat data;
      const std::string& e = encodings[i];
      if (e == "rgb8") cv::cvtColor(bgr, data, cv::COLOR_BGR2RGB);
      if (e == "bgra8") cv::cvtColor(bgr, data, cv::COLOR_BGR2BGRA);
      if (e == "rgba8") cv::cvtColor(bgr, data, cv::COLOR_BGR2RGBA);
      if (e == "mono8") cv::cvtColor(bgr, data, cv::COLOR_BGR2GRAY);
      if (e == "bgr8" || e == "8UC3") data = bgr;
      bag.WriteImage("/cam0/image_raw", 100.0 + 0.05 * i, data, e);
    }
  }
  RosbagSource source(path, BagOptions("/cam0/image_raw"));
  EXPECT_EQ(source.SizeHint(), encodings.size());
  EXPECT_THAT(source.Describe(), HasSubstr("/cam0/image_raw"));
  for (size_t i = 0; i < encodings.size(); ++i) {
    const std::optional<Frame> frame = source.Next();
    ASSERT_TRUE(frame) << encodings[i];
    EXPECT_EQ(frame->index, int(i));
    EXPECT_DOUBLE_EQ(frame->t_s, ros::Time(100.0 + 0.05 * i).toSec());
    cv::Mat expected = Pattern(int(i));
    if (encodings[i] == "mono8") {
      cv::Mat gray;
      cv::cvtColor(expected, gray, cv::COLOR_BGR2GRAY);
      cv::cvtColor(gray, expected, cv::COLOR_GRAY2BGR);
    }
    ExpectSameImage(frame->image, expected);
  }
  EXPECT_FALSE(source.Next());
}

TEST(RosbagSourceTest, CompressedPngFramesDecodeExactlyAndImuSamplesArriveBetweenFrames) {
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "compressed.bag").string();
  {
    TestBagWriter bag(path);
    // IMU at 200 Hz from t = 1 s (rosbag refuses times before ros::TIME_MIN), frames at 20 Hz
    // from t = 1.0125 s: 3 samples before frame 0, 10 between consecutive frames.
    for (int k = 0; k < 40; ++k) {
      bag.WriteImu("/imu0", 1.0 + 0.005 * k, Eigen::Vector3d(0.1 * k, 0.0, 9.81),
                   Eigen::Vector3d(0, 0, k));
    }
    for (int i = 0; i < 3; ++i) {
      bag.WriteCompressedImage("/cam0/image_raw/compressed", 1.0125 + 0.05 * i, Pattern(i), ".png");
    }
  }
  RosbagSource source(path, BagOptions("/cam0/image_raw/compressed", ColorMode::kColor, "/imu0"));
  std::vector<ImuSample> all;
  for (int i = 0; i < 3; ++i) {
    const std::optional<Frame> frame = source.Next();
    ASSERT_TRUE(frame);
    ExpectSameImage(frame->image, Pattern(i));
    const std::vector<ImuSample> imu = source.TakeImuSamples();
    ASSERT_EQ(imu.size(), i == 0 ? 3u : 10u) << "frame " << i;
    for (const ImuSample& sample : imu) EXPECT_LT(sample.t_s, frame->t_s);
    all.insert(all.end(), imu.begin(), imu.end());
  }
  EXPECT_FALSE(source.Next());
  const std::vector<ImuSample> rest = source.TakeImuSamples();  // after the last frame
  EXPECT_EQ(all.size() + rest.size(), 40u);
  for (size_t k = 0; k < all.size(); ++k) {
    EXPECT_DOUBLE_EQ(all[k].t_s, ros::Time(1.0 + 0.005 * k).toSec());
    EXPECT_DOUBLE_EQ(all[k].specific_force_B.x(), 0.1 * k);
    EXPECT_DOUBLE_EQ(all[k].omega_B.z(), double(k));
  }
}

TEST(RosbagSourceTest, OpenFrameSourceReadsABagInTheColourModeAsked) {
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "gray.bag").string();
  {
    TestBagWriter bag(path);
    bag.WriteImage("/cam", 1.0, Pattern(1), "bgr8");
  }
  const std::unique_ptr<FrameSource> source =
      OpenFrameSource(path, BagOptions("/cam", ColorMode::kGray));
  const std::optional<Frame> frame = source->Next();
  ASSERT_TRUE(frame);
  cv::Mat gray;
  cv::cvtColor(Pattern(1), gray, cv::COLOR_BGR2GRAY);
  ExpectSameImage(frame->image, gray);
}

TEST(RosbagSourceTest, BadInputNamesTheTopicTheEncodingOrTheTime) {
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "bad.bag").string();
  {
    TestBagWriter bag(path);
    // Received in this order, stamped going back in time.
    bag.WriteImage("/cam0/image_raw", 2.0, Pattern(0), "bgr8", 1.0);
    bag.WriteImage("/cam0/image_raw", 1.0, Pattern(1), "bgr8", 1.5);
    cv::Mat depth(24, 32, CV_16UC1, cv::Scalar(1000));
    bag.WriteImage("/depth", 1.0, depth, "16UC1");
    bag.WriteImu("/imu0", 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  }
  const std::string missing = MessageOf([&] { RosbagSource(path, BagOptions("/cam1/image_raw")); });
  EXPECT_THAT(missing, HasSubstr("no topic '/cam1/image_raw'"));
  EXPECT_THAT(missing, HasSubstr("/cam0/image_raw (sensor_msgs/Image)"));  // lists what there is
  EXPECT_THAT(MessageOf([&] { RosbagSource(path, BagOptions("")); }), HasSubstr("--image-topic"));
  EXPECT_THAT(MessageOf([&] { RosbagSource(path, BagOptions("/imu0")); }),
              HasSubstr("'/imu0' carries sensor_msgs/Imu"));
  EXPECT_THAT(MessageOf([&] {
                RosbagSource(path, BagOptions("/cam0/image_raw", ColorMode::kColor, "/imu1"));
              }),
              HasSubstr("no topic '/imu1'"));

  RosbagSource depth(path, BagOptions("/depth"));
  const std::string encoding = MessageOf([&] { depth.Next(); });
  EXPECT_THAT(encoding, HasSubstr("encoding '16UC1'"));
  EXPECT_THAT(encoding, HasSubstr("topic '/depth'"));

  RosbagSource backwards(path, BagOptions("/cam0/image_raw"));
  ASSERT_TRUE(backwards.Next());
  EXPECT_THAT(MessageOf([&] { backwards.Next(); }), HasSubstr("does not increase"));

  EXPECT_THAT(MessageOf<std::runtime_error>(
                  [&] { RosbagSource((dir.path() / "missing.bag").string(), BagOptions("/cam")); }),
              HasSubstr("missing.bag"));
}

TEST(RosbagSourceTest, CameraInfoGivesTheCameraItDescribes) {
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "info.bag").string();
  const std::unique_ptr<CameraModel> radtan = CreateCameraModel(
      "radtan", 752, 480, Eigen::Vector4d(458.654, 457.296, 367.215, 248.375),
      (Eigen::VectorXd(4) << -0.28340811, 0.07395907, 0.00019359, 1.76187114e-05).finished());
  const std::unique_ptr<CameraModel> fisheye =
      CreateCameraModel("equidistant", 640, 480, Eigen::Vector4d(280.0, 281.0, 320.5, 240.5),
                        (Eigen::VectorXd(4) << 0.01, -0.002, 0.0005, -0.0001).finished());
  {
    TestBagWriter bag(path);
    bag.WriteCameraInfo("/cam0/camera_info", 1.0, *radtan);
    bag.WriteCameraInfo("/cam1/camera_info", 1.0, *fisheye);
    bag.WriteImage("/cam0/image_raw", 1.0, Pattern(0), "bgr8");
  }
  for (const auto& [topic, camera] : {std::pair{"/cam0/camera_info", radtan.get()},
                                      std::pair{"/cam1/camera_info", fisheye.get()}}) {
    const CameraCalibration calibration = LoadCameraInfoFromBag(path, topic);
    EXPECT_EQ(calibration.camera->model_name(), camera->model_name());
    EXPECT_EQ(calibration.camera->width(), camera->width());
    EXPECT_EQ(calibration.camera->intrinsics(), camera->intrinsics());
    EXPECT_EQ(calibration.camera->distortion().head(4), camera->distortion().head(4));
    EXPECT_THAT(calibration.source_path, HasSubstr(topic));
  }
  EXPECT_THAT(MessageOf([&] { LoadCameraInfoFromBag(path, "/cam0/image_raw"); }),
              HasSubstr("carries sensor_msgs/Image, not sensor_msgs/CameraInfo"));
}

}  // namespace
}  // namespace aperture::perception
