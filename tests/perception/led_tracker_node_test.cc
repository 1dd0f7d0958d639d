#include "perception/led/led_tracker_node.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "config/config_tree.h"
#include "control/so3.h"
#include "led_test_images.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/serial_executor.h"
#include "perception/sensor_data.h"
#include "temp_directory.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using test_support::MessageOf;

using ::testing::HasSubstr;

FrontEndResources LedNodeResources() {
  FrontEndResources resources;
  CameraCalibration calibration;
  calibration.camera =
      std::make_shared<PinholeCamera>(752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
  resources.calibration = calibration;
  return resources;
}

TEST(LedTrackerNodeTest, ReportsThePoseStreamWithCovarianceMetricsAndOverlay) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  const FrontEndResources resources = LedNodeResources();
  config::ConfigTree tree;
  tree.ApplySet("led.p3p=ap3p");
  config::ParamReader root = tree.Reader();
  FrameGraph graph = registry.BuildGraph({"led"}, root, resources);
  SerialExecutor executor(graph);

  const LedConfiguration configuration = LedConfiguration::Default();
  const Eigen::Isometry3d T_CT =
      control::ExpSe3((control::Vector6d() << -0.1, 0.05, 1.3, 0.3, -0.2, 0.1).finished());
  std::vector<Eigen::Vector2d> px;
  for (const auto& p_T : configuration.p_T()) {
    px.emplace_back();
    ASSERT_TRUE(resources.calibration->camera->Project(T_CT * p_T, &px.back()));
  }
  Frame frame;
  frame.image = test_support::BlobImage(752, 480, px, 2.0);
  FrameSlots slots = executor.Run(frame);
  const NodeContext context = graph.ContextFor(0, slots);
  const std::vector<PoseObservation> poses = graph.node(0).Poses(context);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].stream, "led");
  EXPECT_EQ(poses[0].fixed, PoseObservation::Fixed::kCamera);
  EXPECT_LT((poses[0].T_CX.translation() - T_CT.translation()).norm(), 0.003);
  EXPECT_TRUE(poses[0].T_fixed_moving().isApprox(poses[0].T_CX));  // the stream records T_CT
  ASSERT_TRUE(poses[0].covariance_CX.has_value());
  const auto metrics = graph.node(0).Metrics(context);
  EXPECT_EQ(metrics.at("detections"), 5.0);
  EXPECT_EQ(metrics.at("correspondences"), 5.0);
  EXPECT_EQ(metrics.at("status"), static_cast<double>(LedTrackStatus::kReinitialized));
  cv::Mat bgr(480, 752, CV_8UC3, cv::Scalar(0, 0, 0));
  graph.node(0).DrawOverlay(context, bgr);
  EXPECT_GT(cv::countNonZero(bgr.reshape(1)), 100);  // markers, axes and text were drawn

  // A dark frame: no pose, the same metric keys with NaN rms.
  frame.image = cv::Mat::zeros(480, 752, CV_8UC1);
  frame.t_s = 0.05;
  FrameSlots dark = executor.Run(frame);
  const NodeContext dark_context = graph.ContextFor(0, dark);
  EXPECT_TRUE(graph.node(0).Poses(dark_context).empty());
  const auto dark_metrics = graph.node(0).Metrics(dark_context);
  EXPECT_EQ(dark_metrics.size(), metrics.size());
  EXPECT_TRUE(std::isnan(dark_metrics.at("rms_px")));
}

TEST(LedTrackerNodeTest, NeedsACalibrationAndAValidConfiguration) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  EXPECT_THAT(MessageOf([&] { registry.Create("led"); }), HasSubstr("--calib"));
  test_support::TempDirectory dir;
  const std::string path = (dir.path() / "square.yaml").string();
  std::ofstream(path) << "leds: [[0.1, 0, 0], [0, 0.1, 0], [-0.1, 0, 0], [0, -0.1, 0]]\n";
  config::ConfigTree tree;
  tree.ApplySet("config=" + path);
  config::ParamReader params = tree.Reader();
  EXPECT_THAT(MessageOf([&] { registry.Create("led", params, LedNodeResources()); }),
              ::testing::AllOf(HasSubstr("square.yaml"), HasSubstr("coplanar")));
  config::ConfigTree bad_method;
  bad_method.ApplySet("p3p=epnp");
  config::ParamReader bad_params = bad_method.Reader();
  EXPECT_THAT(MessageOf([&] { registry.Create("led", bad_params, LedNodeResources()); }),
              HasSubstr("epnp"));
}

}  // namespace
}  // namespace aperture::perception
