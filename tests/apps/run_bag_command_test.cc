// `aperture run` on a ROS1 bag end to end: a bag the test writes from a rendered image folder
// (images, their times, the camera_info of its calibration and an IMU topic) replays through
// `--frontends gap` with the same poses as the folder itself, its IMU samples land in imu.csv
// and reach the ts2p front end (it derotates with them), and bad topics fail the run naming them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "perception/camera/calibration_io.h"
#include "perception/io/image_file_reader.h"
#include "tests/apps/cli_runner.h"
#include "tests/support/test_bag_writer.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// rosbag rejects stamps before ros::TIME_MIN; the rendered sequence starts at t = 0.
constexpr double kBagStartS = 100.0;

// Rows of a TUM file (`<stream>.csv`): t tx ty tz qx qy qz qw.
std::vector<std::vector<double>> ReadTumRows(const fs::path& path) {
  std::ifstream file(path);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::vector<double> row(8);
    for (double& value : row) in >> value;
    rows.push_back(row);
  }
  return rows;
}

// The folder `aperture render` wrote, as a bag: /cam0/image_raw (mono8), /cam0/camera_info,
// /imu0 at 200 Hz over the sequence. Returns the number of IMU samples written.
int WriteBagFromFolder(const fs::path& folder, const fs::path& bag_path) {
  const perception::CameraCalibration calibration =
      perception::LoadCameraCalibration((folder / "calib.yaml").string());
  std::ifstream times(folder / "images" / "times.txt");
  std::vector<double> t_s;
  for (double t; times >> t;) t_s.push_back(t);
  test_support::TestBagWriter bag(bag_path.string());
  bag.WriteCameraInfo("/cam0/camera_info", kBagStartS, *calibration.camera);
  int imu_samples = 0;
  for (double t = 0.0; t <= t_s.back() + 1e-9; t += 0.005, ++imu_samples) {
    bag.WriteImu("/imu0", kBagStartS + t, Eigen::Vector3d(0.0, 0.0, 9.81), Eigen::Vector3d::Zero());
  }
  for (size_t i = 0; i < t_s.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06zu.png", i);
    const cv::Mat image =
        perception::ReadImageFile(folder / "images" / name, perception::ColorMode::kGray);
    bag.WriteImage("/cam0/image_raw", kBagStartS + t_s[i], image, "mono8");
  }
  return imu_samples;
}

// TS²P on stacks of 2 frames, from the third frame on, every frame.
const std::string kTs2pEveryFrame = " --set ts2p.stack=2 --set ts2p.stride=1 --set ts2p.interval=1";

TEST(RunBagCommandTest, BagReplaysWithTheSamePosesAsItsImageFolder) {
  TempFolder temp("run_bag");
  const fs::path folder = fs::path(temp.path()) / "render";
  ASSERT_EQ(RunAperture("render gap --frames 4 --out " + folder.string()).exit_code, 0);
  const fs::path bag = fs::path(temp.path()) / "gap.bag";
  const int imu_written = WriteBagFromFolder(folder, bag);

  const fs::path from_folder = fs::path(temp.path()) / "folder_run";
  const CommandResult folder_run = RunAperture(
      "run --source " + folder.string() + " --calib " + (folder / "calib.yaml").string() +
      " --frontends gap,ts2p" + kTs2pEveryFrame + " --out " + from_folder.string());
  ASSERT_EQ(folder_run.exit_code, 0) << folder_run.output;
  const fs::path from_bag = fs::path(temp.path()) / "bag_run";
  const CommandResult bag_run =
      RunAperture("run --source " + bag.string() +
                  " --image-topic /cam0/image_raw --imu-topic /imu0 "
                  "--camera-info-topic /cam0/camera_info --frontends gap,ts2p" +
                  kTs2pEveryFrame + " --out " + from_bag.string());
  ASSERT_EQ(bag_run.exit_code, 0) << bag_run.output;

  const auto folder_poses = ReadTumRows(from_folder / "gap.csv");
  const auto bag_poses = ReadTumRows(from_bag / "gap.csv");
  ASSERT_EQ(folder_poses.size(), 4u);  // the gap is in view in every frame
  ASSERT_EQ(bag_poses.size(), folder_poses.size());
  for (size_t i = 0; i < bag_poses.size(); ++i) {
    // Bag stamps are integer nanoseconds.
    EXPECT_NEAR(bag_poses[i][0] - kBagStartS, folder_poses[i][0], 1e-6) << "frame " << i;
    for (int k = 1; k < 8; ++k) {
      // The same pixels and camera give the same detection; the TUM text keeps ~1e-9.
      EXPECT_NEAR(bag_poses[i][k], folder_poses[i][k], 1e-9) << "frame " << i << " column " << k;
    }
  }
  const nlohmann::json summary = ReadJson((from_bag / "summary.json").string());
  EXPECT_EQ(summary["frames"], 4);
  EXPECT_NE(summary["inputs"]["source_description"].get<std::string>().find("/imu0"),
            std::string::npos);
  // IMU samples up to the last frame (the ones after it are never asked for).
  const int imu_in_run = summary["imu_samples"].get<int>();
  EXPECT_GT(imu_in_run, imu_written - 2);
  EXPECT_EQ(CountLines((from_bag / "imu.csv").string()), size_t(imu_in_run) + 1);  // + header
  // The frames carried their IMU samples to ts2p: its last detection (frames 1-3, all after the
  // first sample) was derotated; the image folder has no IMU, so none of its detections was.
  EXPECT_EQ(summary["metrics"]["ts2p.derotated"]["max"], 1.0) << summary["metrics"].dump();
  const nlohmann::json folder_summary = ReadJson((from_folder / "summary.json").string());
  EXPECT_EQ(folder_summary["metrics"]["ts2p.derotated"]["max"], 0.0);
}

TEST(RunBagCommandTest, MissingTopicsFailTheRunNamingThem) {
  TempFolder temp("run_bag_bad");
  const fs::path bag = fs::path(temp.path()) / "small.bag";
  {
    test_support::TestBagWriter writer(bag.string());
    writer.WriteImage("/cam0/image_raw", 1.0, cv::Mat(24, 32, CV_8UC1, cv::Scalar(128)), "mono8");
  }
  const CommandResult no_topic =
      RunAperture("run --source " + bag.string() + " --out " + temp.path() + "/a");
  EXPECT_EQ(no_topic.exit_code, 1);
  EXPECT_NE(no_topic.output.find("--image-topic"), std::string::npos) << no_topic.output;
  const CommandResult wrong_topic =
      RunAperture("run --source " + bag.string() + " --image-topic /cam1/image_raw --out " +
                  temp.path() + "/b");
  EXPECT_EQ(wrong_topic.exit_code, 1);
  EXPECT_NE(wrong_topic.output.find("no topic '/cam1/image_raw'"), std::string::npos)
      << wrong_topic.output;
  const CommandResult no_info = RunAperture("run --source " + bag.string() +
                                            " --image-topic /cam0/image_raw --camera-info-topic "
                                            "/cam0/camera_info --frontends gap --out " +
                                            temp.path() + "/c");
  EXPECT_EQ(no_info.exit_code, 1);
  EXPECT_NE(no_info.output.find("no topic '/cam0/camera_info'"), std::string::npos)
      << no_info.output;
}

}  // namespace
}  // namespace aperture::apps::testing
