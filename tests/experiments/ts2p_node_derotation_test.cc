// The ts2p front end with a gyro: frames that carry IMU samples (Frame::imu, as `aperture run`
// hands them from a bag) are derotated with the integrated rates through the calibration's T_BC.
// A rendered scan that yaws while it translates: the node's detection equals the detector's with
// the true rotations, and finds the opening where the same frames without IMU do worse.
#include <gtest/gtest.h>

#include <cmath>

#include "config/config_tree.h"
#include "control/so3.h"
#include "experiments/ts2p/ts2p_scan.h"
#include "perception/camera/optical_axes.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/serial_executor.h"
#include "perception/ts2p/opening_score.h"
#include "perception/ts2p/ts2p_node.h"

namespace aperture::experiments {
namespace {

constexpr double kFrameRateHz = 30.0;
constexpr double kImuRateHz = 200.0;

// Forward-looking camera: z_C = x_B, x_C = -y_B, y_C = -z_B.
Eigen::Isometry3d ForwardCamera_T_BC() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = perception::OpticalAxesAlongX();
  T_BC.translation() = Eigen::Vector3d(0.1, 0.0, 0.02);
  return T_BC;
}

class Ts2pNodeDerotationTest : public ::testing::Test {
 protected:
  Ts2pNodeDerotationTest() {
    config_.shape = "polygon";
    config_.seed = 4;
    config_.scan_step_m = 0.05;
    config_.rotation_per_step_deg = Eigen::Vector3d(0.0, 0.0, kYawPerStepDeg);  // about y_C
    sim::RayCaster caster;
    scan_ = RenderTs2pScan(config_, caster);
    calibration_.camera = scan_.camera;
    calibration_.T_BC = ForwardCamera_T_BC();
  }

  // The scan in time order (stack frames around the reference), 30 Hz, each frame with the gyro
  // samples since the previous one when `with_imu`: the camera turns at a constant rate about
  // y_C (R_WC(t) = R_WCr Ry(yaw_per_step * 30 t)), seen by the body's gyro through R_BC.
  std::vector<perception::Frame> Frames(bool with_imu) const {
    std::vector<cv::Mat> images = scan_.frames;
    images.insert(images.begin() + config_.stack / 2, scan_.reference);
    const Eigen::Vector3d omega_C(0.0, kYawPerStepDeg * M_PI / 180.0 * kFrameRateHz, 0.0);
    const Eigen::Vector3d omega_B = calibration_.T_BC.linear() * omega_C;
    std::vector<perception::Frame> frames;
    double t_imu_s = -0.02;
    for (std::size_t k = 0; k < images.size(); ++k) {
      perception::Frame frame;
      frame.index = static_cast<int>(k);
      frame.t_s = k / kFrameRateHz;
      frame.image = images[k];
      for (; with_imu && t_imu_s <= frame.t_s + 1e-12; t_imu_s += 1.0 / kImuRateHz) {
        frame.imu.push_back({t_imu_s, Eigen::Vector3d(0.0, 0.0, 9.81), omega_B});
      }
      frames.push_back(frame);
    }
    return frames;
  }

  // Runs the "ts2p" front end (stack 4, stride 1) over `frames`; returns its last output.
  perception::Ts2pOutput RunNode(const std::vector<perception::Frame>& frames,
                                 bool with_calibration, const std::string& set = "") const {
    perception::FrontEndRegistry registry;
    perception::RegisterBuiltinFrontEnds(registry);
    perception::FrontEndResources resources;
    if (with_calibration) resources.calibration = calibration_;
    config::ConfigTree tree;
    tree.ApplySet("ts2p.stride=1");
    if (!set.empty()) tree.ApplySet(set);
    config::ParamReader root = tree.Reader();
    perception::FrameGraph graph = registry.BuildGraph({"ts2p"}, root, resources);
    perception::SerialExecutor executor(graph);
    perception::Ts2pOutput output;
    for (const perception::Frame& frame : frames) {
      perception::FrameSlots slots = executor.Run(frame);
      const perception::NodeContext context = graph.ContextFor(0, slots);
      output = context.Get<perception::Ts2pOutput>(perception::Ts2pNode::kOutputSlot);
    }
    return output;
  }

  static constexpr double kYawPerStepDeg = 1.5;  // ~9 px of rotational flow per step
  Ts2pScanConfig config_;
  Ts2pScan scan_;
  perception::CameraCalibration calibration_;
};

TEST_F(Ts2pNodeDerotationTest, DerotatesWithTheGyroAsWithTheTrueRotations) {
  const perception::Ts2pOutput with_imu = RunNode(Frames(true), true);
  ASSERT_TRUE(with_imu.fresh);
  ASSERT_TRUE(with_imu.detection);
  EXPECT_TRUE(with_imu.derotated);
  EXPECT_EQ(with_imu.reference_index, config_.stack / 2);

  // The integrated gyro gives the scan's own rotations: the same detection as the detector's.
  perception::Ts2pDetector detector(perception::Ts2pParams{}, scan_.camera);
  const perception::Ts2pDetection truth_rotations =
      detector.Detect(scan_.reference, scan_.frames, scan_.R_CkCr);
  ASSERT_TRUE(truth_rotations.valid) << truth_rotations.status;
  ASSERT_TRUE(with_imu.detection->valid) << with_imu.detection->status;
  EXPECT_NEAR(with_imu.detection->area_px, truth_rotations.area_px, 0.01 * truth_rotations.area_px);

  const perception::OpeningScore derotated =
      perception::ScoreOpening(with_imu.detection->opening, scan_.truth);
  EXPECT_GE(derotated.overlap, perception::OpeningScore::kDetectionOverlap);
  EXPECT_LE(derotated.false_positive, 0.04);

  // Without the gyro the rotation reads as parallax: much of the wall is called opening (here
  // ~30 % of it, against < 1 % derotated).
  const perception::Ts2pOutput without_imu = RunNode(Frames(false), true);
  ASSERT_TRUE(without_imu.fresh);
  EXPECT_FALSE(without_imu.derotated);
  if (without_imu.detection->valid) {
    const perception::OpeningScore raw =
        perception::ScoreOpening(without_imu.detection->opening, scan_.truth);
    EXPECT_GT(raw.false_positive, 0.1) << "overlap " << raw.overlap;
  }

  // Switched off, the IMU is ignored: the raw detection.
  const perception::Ts2pOutput off = RunNode(Frames(true), false, "ts2p.gyro_derotation=false");
  EXPECT_FALSE(off.derotated);
  EXPECT_EQ(off.detection->area_px, without_imu.detection->area_px);
}

TEST_F(Ts2pNodeDerotationTest, ImuWithoutCalibrationIsAnErrorNamingTheFixes) {
  try {
    RunNode(Frames(true), false);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("--calib"), std::string::npos) << message;
    EXPECT_NE(message.find("ts2p.gyro_derotation=false"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace aperture::experiments
