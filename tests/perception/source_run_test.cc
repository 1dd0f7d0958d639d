// RunSource: the frame loop of `aperture run` and the Python module — frames through the graph,
// the handler after each, the frame limit, and the errors for an empty source and a calibration
// of another image size.
#include "perception/graph/source_run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "perception/camera/pinhole_camera.h"
#include "perception/gap/gap_node.h"
#include "perception/graph/serial_executor.h"
#include "perception/io/in_process_source.h"
#include "tests/perception/gap_test_images.h"

namespace aperture::perception {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::shared_ptr<const CameraModel> CenteredPinhole(int width, int height) {
  return std::make_shared<PinholeCamera>(
      width, height, PinholeIntrinsics{420.0, 420.0, 0.5 * width - 0.5, 0.5 * height - 0.5});
}

class SourceRunTest : public ::testing::Test {
 protected:
  SourceRunTest() : camera_(CenteredPinhole(752, 480)), graph_(Nodes()), executor_(graph_) {
    resources_.calibration = CameraCalibration{camera_, Eigen::Isometry3d::Identity(), "cam0", ""};
  }

  std::vector<std::unique_ptr<Node>> Nodes() const {
    std::vector<std::unique_ptr<Node>> nodes;
    nodes.push_back(std::make_unique<GapNode>(GapDetectorParams{}, CenteredPinhole(752, 480)));
    return nodes;
  }

  // Gap views 3 m ahead, shifted sideways by 0.1 m per frame.
  void PushGapFrames(int count) {
    for (int i = 0; i < count; ++i) {
      Eigen::Isometry3d T_CG = Eigen::Isometry3d::Identity();
      T_CG.translation() = Eigen::Vector3d(0.1 * i, 0.0, 3.0);
      Frame frame;
      frame.t_s = 0.1 * i;
      frame.index = i;
      frame.image = DrawGapPattern(*camera_, GapDetectorParams{}, T_CG);
      source_.Push(frame);
    }
    source_.Close();
  }

  std::shared_ptr<const CameraModel> camera_;
  FrameGraph graph_;
  SerialExecutor executor_;
  FrontEndResources resources_;
  InProcessSource source_{FrameSourceOptions{}, "test frames"};
};

TEST_F(SourceRunTest, HandsEachFrameToTheHandlerAfterTheNodesRan) {
  PushGapFrames(3);
  std::vector<double> x_m;
  const std::size_t frames = RunSource(
      source_, graph_, executor_, resources_, 0, [&](const Frame& frame, const FrameSlots& slots) {
        const std::vector<PoseObservation> poses = graph_.CollectPoses(slots);
        ASSERT_EQ(poses.size(), 1u) << "frame " << frame.index;
        EXPECT_EQ(poses[0].t_s, frame.t_s);
        x_m.push_back(poses[0].T_CX.translation().x());
      });
  EXPECT_EQ(frames, 3u);
  ASSERT_EQ(x_m.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(x_m[i], 0.1 * i, 0.01) << "frame " << i;
}

TEST_F(SourceRunTest, StopsAtTheFrameLimit) {
  PushGapFrames(3);
  int seen = 0;
  EXPECT_EQ(RunSource(source_, graph_, executor_, resources_, 2,
                      [&](const Frame&, const FrameSlots&) { ++seen; }),
            2u);
  EXPECT_EQ(seen, 2);
}

TEST_F(SourceRunTest, AnEmptySourceIsAnErrorNamingIt) {
  source_.Close();
  try {
    RunSource(source_, graph_, executor_, resources_, 0, [](const Frame&, const FrameSlots&) {});
    FAIL() << "an empty source must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("test frames"), HasSubstr("no frames")));
  }
}

TEST_F(SourceRunTest, ACalibrationOfAnotherImageSizeIsRejectedBeforeAnyNodeRuns) {
  resources_.calibration->camera = CenteredPinhole(640, 480);
  PushGapFrames(1);
  int seen = 0;
  try {
    RunSource(source_, graph_, executor_, resources_, 0,
              [&](const Frame&, const FrameSlots&) { ++seen; });
    FAIL() << "a 640x480 calibration for 752x480 frames must throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("640"), HasSubstr("752")));
  }
  EXPECT_EQ(seen, 0);
}

}  // namespace
}  // namespace aperture::perception
