// FrontEndRunner: the front ends of `aperture run` inside an autopilot — pose observations per
// frame, the latest slot values, overlays, registry construction.
#include "perception/graph/front_end_runner.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "config/config_tree.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/gap/gap_node.h"
#include "perception/graph/builtin_front_ends.h"
#include "tests/perception/gap_test_images.h"
#include "tests/support/pinhole_752x480.h"

namespace aperture::perception {
namespace {

Frame GapFrame(const CameraModel& camera, const Eigen::Isometry3d& T_CG, double t_s) {
  Frame frame;
  frame.t_s = t_s;
  frame.image = DrawGapPattern(camera, GapDetectorParams{}, T_CG);
  return frame;
}

TEST(FrontEndRunnerTest, HandsOnEachFramesPoseObservationsStampedWithTheFrameTime) {
  const auto camera = test_support::Pinhole752x480();
  std::vector<std::unique_ptr<Node>> nodes;
  nodes.push_back(std::make_unique<GapNode>(GapDetectorParams{}, camera));
  FrontEndRunner runner(std::move(nodes));
  EXPECT_EQ(runner.Latest<GapDetection>(GapNode::kOutputSlot), nullptr);  // before a frame

  Eigen::Isometry3d T_CG = Eigen::Isometry3d::Identity();
  T_CG.translation() = Eigen::Vector3d(0.1, -0.05, 3.0);
  const std::vector<PoseObservation>& seen = runner.Process(GapFrame(*camera, T_CG, 0.25));
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].stream, "gap");
  EXPECT_EQ(seen[0].t_s, 0.25);
  EXPECT_LT((seen[0].T_CX.translation() - T_CG.translation()).norm(), 0.015);  // 0.5 % of 3 m
  const GapDetection* detection = runner.Latest<GapDetection>(GapNode::kOutputSlot);
  ASSERT_NE(detection, nullptr);
  EXPECT_TRUE(detection->detected());
  cv::Mat overlay(camera->height(), camera->width(), CV_8UC3, cv::Scalar::all(0));
  runner.DrawOverlays(overlay);
  EXPECT_GT(cv::countNonZero(overlay.reshape(1)), 0);

  // An empty view: no observation, and the latest detection says so.
  Frame empty;
  empty.t_s = 0.3;
  empty.image = cv::Mat(camera->height(), camera->width(), CV_8UC1, cv::Scalar(128));
  EXPECT_TRUE(runner.Process(empty).empty());
  EXPECT_FALSE(runner.Latest<GapDetection>(GapNode::kOutputSlot)->detected());
  EXPECT_EQ(runner.frames(), 2);
  EXPECT_THROW(runner.Latest<double>(GapNode::kOutputSlot), std::invalid_argument);  // wrong type
}

TEST(FrontEndRunnerTest, BuildsFromTheRegistryLikeApertureRun) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  FrontEndResources resources;
  resources.calibration =
      CameraCalibration{test_support::Pinhole752x480(), Eigen::Isometry3d::Identity(), "cam0", ""};
  const config::ConfigTree tree =
      config::ConfigTree::FromCommandLine("", {}, {"image_quality.histogram_bins=16"});
  config::ParamReader root = tree.Reader();
  FrontEndRunner runner =
      FrontEndRunner::FromRegistry(registry, {"image_quality", "gap"}, root, resources);
  EXPECT_EQ(runner.graph().size(), 2u);
  const config::ConfigTree bad = config::ConfigTree::FromCommandLine("", {}, {"gap.no_such=1"});
  config::ParamReader bad_root = bad.Reader();
  EXPECT_THROW(FrontEndRunner::FromRegistry(registry, {"gap"}, bad_root, resources),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
