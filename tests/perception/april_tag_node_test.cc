#include "perception/tags/april_tag_node.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "config/config_tree.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/serial_executor.h"
#include "perception/sensor_data.h"
#include "temp_directory.h"

namespace aperture::perception {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kPhoto =
    std::filesystem::path(std::getenv("VISP_INPUT_IMAGE_PATH")
                              ? std::getenv("VISP_INPUT_IMAGE_PATH")
                              : "/usr/share/visp-images-data") /
    "ViSP-images" / "AprilTag" / "AprilTag.pgm";

FrontEndResources TagNodeResources(const std::string& output_directory = "") {
  FrontEndResources resources;
  CameraCalibration calibration;
  // ViSP's testAprilTag.cpp intrinsics of the photo.
  calibration.camera = std::make_shared<PinholeCamera>(
      640, 480, PinholeIntrinsics{615.1674805, 615.1675415, 312.1889954, 243.4373779});
  resources.calibration = calibration;
  resources.output_directory = output_directory;
  return resources;
}

std::string TagNodeErrorOf(const std::function<void()>& body) {
  try {
    body();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(AprilTagNode, WritesTagsCsvPoseStreamsAndTheMap) {
  if (!std::filesystem::exists(kPhoto)) GTEST_SKIP() << "visp-images-data not installed";
  const test_support::TempDirectory dir;
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  config::ConfigTree tree;
  tree.ApplySet("apriltag.size_m=0.053");
  tree.ApplySet("apriltag.map=true");
  tree.ApplySet("apriltag.mapping.origin_id=8");  // the photo shows ids 8-19
  config::ParamReader root = tree.Reader();
  FrameGraph graph = registry.BuildGraph({"apriltag"}, root, TagNodeResources(dir.path().string()));
  SerialExecutor executor(graph);
  Frame frame;
  frame.image = cv::imread(kPhoto.string(), cv::IMREAD_GRAYSCALE);
  frame.t_s = 0.5;
  FrameSlots slots = executor.Run(frame);
  const NodeContext context = graph.ContextFor(0, slots);
  const std::vector<PoseObservation> poses = graph.node(0).Poses(context);
  ASSERT_EQ(poses.size(), 12u);
  for (const PoseObservation& pose : poses) {
    EXPECT_THAT(pose.stream, ::testing::StartsWith("tag"));
    ASSERT_TRUE(pose.covariance_CX);
    EXPECT_EQ(pose.fixed, PoseObservation::Fixed::kTarget);
    EXPECT_GT(pose.T_CX.translation().z(), 0.3);  // 0.37-0.56 m in front of the camera
    EXPECT_LT(pose.T_CX.translation().z(), 0.6);
  }
  const std::map<std::string, double> metrics = graph.CollectMetrics(slots);
  EXPECT_EQ(metrics.at("apriltag.detections"), 12.0);
  EXPECT_EQ(metrics.at("apriltag.posed"), 12.0);
  const std::map<std::string, std::string> files = graph.Finish();
  EXPECT_EQ(files.at("apriltag.detections"), "tags.csv");
  EXPECT_EQ(files.at("apriltag.map"), "tag_map.yaml");

  std::ifstream csv(dir.path() / "tags.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t_s,index,family,id,u0,v0,u1,v1,u2,v2,u3,v3,tx,ty,tz,qx,qy,qz,qw,decision_margin,"
            "ambiguity_ratio,flip_decision,rms_px");
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    EXPECT_THAT(row, HasSubstr(",tag36h11,"));
  }
  EXPECT_EQ(rows, 12);
  // One image: every tag hangs off the origin tag 8 through that image's camera.
  const YAML::Node map = YAML::LoadFile((dir.path() / "tag_map.yaml").string());
  EXPECT_EQ(map["tags"].size(), 12u);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "tag_map.png"));
}

TEST(AprilTagNode, ClearErrorsForMissingInputs) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  auto build = [&](const std::vector<std::string>& sets, const FrontEndResources& resources) {
    config::ConfigTree tree;
    for (const std::string& set : sets) tree.ApplySet(set);
    config::ParamReader root = tree.Reader();
    registry.BuildGraph({"apriltag"}, root, resources);
  };
  EXPECT_THAT(TagNodeErrorOf([&] { build({}, TagNodeResources()); }), HasSubstr("apriltag.size_m"));
  EXPECT_THAT(TagNodeErrorOf([&] { build({"apriltag.size_m=0.1"}, FrontEndResources{}); }),
              HasSubstr("--calib"));
  EXPECT_THAT(TagNodeErrorOf([&] {
                build({"apriltag.size_m=0.1", "apriltag.detector=nope"}, TagNodeResources());
              }),
              HasSubstr("apriltag"));
  EXPECT_THAT(TagNodeErrorOf([&] {
                build({"apriltag.size_m=0.1", "apriltag.families=[tag99h1]"}, TagNodeResources());
              }),
              HasSubstr("tag99h1"));
  EXPECT_THAT(TagNodeErrorOf([&] {
                build({"apriltag.size_m=0.1", "apriltag.sizes.x=0.2"}, TagNodeResources());
              }),
              HasSubstr("tag ids"));
  EXPECT_THAT(TagNodeErrorOf([&] {
                build({"apriltag.size_m=0.1", "apriltag.typo=1"}, TagNodeResources());
              }),
              HasSubstr("typo"));
}

}  // namespace
}  // namespace aperture::perception
