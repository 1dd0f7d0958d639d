// GapDetector and GapNode without the renderer: parameter checks, a pattern drawn with OpenCV
// through an exact pinhole projection, the symmetry convention, the covariance transform.
#include "perception/gap/gap_detector.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "perception/camera/pinhole_camera.h"
#include "perception/gap/gap_node.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/frame_graph.h"
#include "perception/sensor_data.h"
#include "tests/perception/gap_test_images.h"
#include "tests/support/pinhole_752x480.h"

namespace aperture::perception {
namespace {

Eigen::Isometry3d MakePose(double roll, double pitch, double yaw, const Eigen::Vector3d& p_CG) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = p_CG;
  return T;
}

TEST(GapDetectorTest, RejectsInvalidParameters) {
  GapDetectorParams p;
  p.inner_size_m.x() = 0.7;  // smaller than the opening
  try {
    ValidateGapDetectorParams(p);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inner_size_m.x"), std::string::npos) << e.what();
  }
  p = GapDetectorParams{};
  p.canny_high = 10.0;  // below canny_low
  EXPECT_THROW(ValidateGapDetectorParams(p), std::invalid_argument);
  EXPECT_THROW(GapDetector(GapDetectorParams{}, nullptr), std::invalid_argument);
  GapDetector detector(GapDetectorParams{}, test_support::Pinhole752x480());
  EXPECT_THROW(detector.Detect(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
}

TEST(GapDetectorTest, DrawnPatternGivesExactPoseWithSymmetryConvention) {
  const auto camera = test_support::Pinhole752x480();
  GapDetectorParams params;
  GapDetector detector(params, camera);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 8; ++trial) {
    const double distance = 1.5 + 0.4 * trial;
    const Eigen::Isometry3d T_CG =
        MakePose(0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng),
                 Eigen::Vector3d(0.15 * distance * u(rng), 0.1 * distance * u(rng), distance));
    const cv::Mat image = DrawGapPattern(*camera, params, T_CG);
    const GapDetection d = detector.DetectFullImage(image);
    ASSERT_TRUE(d.detected()) << "trial " << trial << ": " << GapDetectionStatusName(d.status);
    // cv::fillConvexPoly includes boundary pixels: each drawn edge lies up to one fine pixel
    // (1/8 px) outside the true one, which biases the corners ~0.1 px outwards and the pose by
    // up to ~0.3 % / 0.3 deg (the renderer test measures the detector's own accuracy).
    EXPECT_LT((d.T_CG.translation() - T_CG.translation()).norm(), 5e-3 * distance)
        << "trial " << trial;
    EXPECT_LT(Eigen::AngleAxisd(d.T_CG.linear().transpose() * T_CG.linear()).angle(),
              0.5 * M_PI / 180)
        << "trial " << trial;
    EXPECT_LT(d.corner_rms_px, 0.3);
    ASSERT_EQ(d.corners_px.size(), 8u);
    // Corner labels follow G: corner i is the projection of model corner i.
    for (int i = 0; i < 8; ++i) {
      Eigen::Vector2d expected;
      ASSERT_TRUE(camera->Project(T_CG * detector.ModelCorners()[i], &expected));
      EXPECT_LT((d.corners_px[i] - expected).norm(), 0.5) << "trial " << trial << " corner " << i;
    }
  }
  // The same gap rotated by 180 deg about z_G is the same image: the detector reports the
  // representative with x_G to the right.
  const Eigen::Isometry3d T_CG = MakePose(0.2, 0.1, 0.0, Eigen::Vector3d(0.0, 0.0, 2.5));
  Eigen::Isometry3d T_flipped = T_CG;
  T_flipped.linear() =
      T_CG.linear() * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const GapDetection d = detector.DetectFullImage(DrawGapPattern(*camera, params, T_flipped));
  ASSERT_TRUE(d.detected());
  EXPECT_GT(d.T_CG.linear()(0, 0), 0.0);
  EXPECT_LT(Eigen::AngleAxisd(d.T_CG.linear().transpose() * T_CG.linear()).angle(),
            0.5 * M_PI / 180);
  // z_G points away from the camera (camera on the -z_G side).
  EXPECT_GT(d.T_CG.linear().col(2).dot(d.T_CG.translation()), 0.0);
}

// Seen from a camera rolled so that x_G points to the image's left, the detector reports the
// image convention's labelling, 180 deg from the truth about z_G; a prediction within 60 deg of
// the truth gets the truth back (and a prediction near the convention keeps it).
TEST(GapDetectorTest, NearestLabellingFollowsThePredictionNotTheImage) {
  const auto camera = test_support::Pinhole752x480();
  GapDetectorParams params;
  GapDetector detector(params, camera);
  const Eigen::Isometry3d T_CG = MakePose(2.2, 0.1, 0.2, Eigen::Vector3d(0.1, -0.05, 2.5));
  ASSERT_LT(T_CG.linear()(0, 0), 0.0);  // x_G to the image's left
  const GapDetection d = detector.DetectFullImage(DrawGapPattern(*camera, params, T_CG));
  ASSERT_TRUE(d.detected());
  const auto angle = [](const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return Eigen::AngleAxisd(a.transpose() * b).angle();
  };
  EXPECT_GT(angle(d.T_CG.linear(), T_CG.linear()), 0.9 * M_PI);
  const Eigen::Matrix3d R_predicted =
      Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix() *
      T_CG.linear();  // 57 deg off the truth
  const Eigen::Isometry3d resolved = NearestGapLabelling(d.T_CG, R_predicted);
  EXPECT_LT(angle(resolved.linear(), T_CG.linear()), 0.5 * M_PI / 180);
  EXPECT_EQ(resolved.translation(), d.T_CG.translation());
  EXPECT_TRUE(NearestGapLabelling(d.T_CG, d.T_CG.linear()).isApprox(d.T_CG, 0.0));
}

TEST(GapNodeTest, RegisteredAndNeedsCalibration) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  ASSERT_TRUE(registry.Contains("gap"));
  EXPECT_THROW(registry.Create("gap"), std::invalid_argument);
  FrontEndResources resources;
  resources.calibration =
      CameraCalibration{test_support::Pinhole752x480(), Eigen::Isometry3d::Identity(), "cam0", ""};
  EXPECT_NE(registry.Create("gap", resources), nullptr);
}

// The node reports T_CG of the fixed target G (the stream records T_GC), its metrics and nothing
// on a miss.
TEST(GapNodeTest, ReportsCameraPoseInGapFrame) {
  const auto camera = test_support::Pinhole752x480();
  std::vector<std::unique_ptr<Node>> nodes;
  nodes.push_back(std::make_unique<GapNode>(GapDetectorParams{}, camera));
  FrameGraph graph(std::move(nodes));
  const Eigen::Isometry3d T_CG = MakePose(0.3, 0.2, -0.1, Eigen::Vector3d(0.1, 0.05, 3.0));
  Frame frame;
  frame.image = DrawGapPattern(*camera, GapDetectorParams{}, T_CG);
  FrameSlots slots = graph.MakeSlots(frame);
  NodeContext context = graph.ContextFor(0, slots);
  graph.node(0).Run(context);
  const std::vector<PoseObservation> poses = graph.CollectPoses(slots);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].stream, "gap");
  EXPECT_EQ(poses[0].fixed, PoseObservation::Fixed::kTarget);
  EXPECT_LT((poses[0].T_CX.translation() - T_CG.translation()).norm(), 0.015);  // 0.5 % of 3 m
  EXPECT_LT((poses[0].T_fixed_moving().translation() - T_CG.inverse().translation()).norm(), 0.015);
  ASSERT_TRUE(poses[0].covariance_CX.has_value());
  const auto metrics = graph.CollectMetrics(slots);
  EXPECT_EQ(metrics.at("gap.detected"), 1.0);
  EXPECT_NEAR(metrics.at("gap.distance_m"), T_CG.translation().norm(), 0.015);
  cv::Mat overlay(camera->height(), camera->width(), CV_8UC3, cv::Scalar::all(0));
  graph.node(0).DrawOverlay(context, overlay);
  EXPECT_GT(cv::countNonZero(overlay.reshape(1)), 0);  // axes and corners drawn

  frame.image = cv::Mat(camera->height(), camera->width(), CV_8UC1, cv::Scalar(128));
  graph.ResetSlots(frame, slots);
  NodeContext empty_context = graph.ContextFor(0, slots);
  graph.node(0).Run(empty_context);
  EXPECT_TRUE(graph.CollectPoses(slots).empty());
  const auto missed = graph.CollectMetrics(slots);
  EXPECT_EQ(missed.at("gap.detected"), 0.0);
  EXPECT_TRUE(std::isnan(missed.at("gap.distance_m")));
}

}  // namespace
}  // namespace aperture::perception
