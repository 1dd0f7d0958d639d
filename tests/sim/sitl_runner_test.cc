// Closed-loop SITL: the ground-truth autopilot through the simulated flight controller (LQR +
// mixer) on the simulated vehicle, with sensors, cameras, latencies, drops and collisions.
#include "sim/sitl/sitl_runner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/scene/textures.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "tests/support/quiet_sitl_params.h"
#include "tests/support/textured_box_scene.h"

namespace aperture::sim {
namespace {

using test_support::HoverAt;

double MaxDeviation(const SitlResult& result, const Eigen::Vector3d& p_W) {
  double max_m = 0.0;
  for (const control::QuadState& s : result.trajectory)
    max_m = std::max(max_m, (s.p_WB - p_W).norm());
  return max_m;
}

// 160 x 120 pinhole, ~90 deg horizontal field of view, looking forward along x_B.
SitlCamera ForwardCamera(double rate_hz) {
  SitlCamera camera;
  camera.name = "front";
  camera.model = std::make_shared<perception::PinholeCamera>(
      160, 120, perception::PinholeIntrinsics{80.0, 80.0, 79.5, 59.5});
  camera.rate_hz = rate_hz;
  // C (x right, y down, z forward) in B (x forward, y left, z up).
  camera.T_BC.linear() = perception::OpticalAxesAlongX();
  camera.effects.full_well_electrons = 2000.0;
  camera.effects.read_noise_sigma = 0.01;
  camera.render.ground_truth = false;
  return camera;
}

using test_support::TexturedBoxScene;

std::uint64_t HashImage(const cv::Mat& image) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  for (int r = 0; r < image.rows; ++r) {
    const unsigned char* row = image.ptr<unsigned char>(r);
    for (size_t i = 0; i < image.cols * image.elemSize(); ++i) {
      hash = (hash ^ row[i]) * 1099511628211ull;
    }
  }
  return hash;
}

TEST(SitlRunner, HoverWithoutNoiseStaysWithinAMillimetre) {
  const SitlRunnerParams params = test_support::QuietSitlParams(10.0);
  SitlRunner runner(params, nullptr);
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  const SitlResult result = runner.Run(autopilot);
  EXPECT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  EXPECT_NEAR(result.sim_time_s, 10.0, 1e-6);
  // Starting exactly in hover with exact sensors, only the discrete-time loops (1 kHz flight
  // controller, 100 Hz autopilot) and rotor lag act: any drift is a modelling mismatch, which at
  // the gains of Table A.2 would show well above 1 mm.
  EXPECT_LT(MaxDeviation(result, params.initial_state.p_WB), 1e-3);
  EXPECT_EQ(result.commands.size(), 1001u);  // 100 Hz over [0, 10] s inclusive
  EXPECT_GT(result.real_time_factor, 0.0);
}

TEST(SitlRunner, HoverWithImuNoiseAndBiasesStaysWithinFewCentimetres) {
  SitlRunnerParams params;  // MPU-6000-class noise and bias random walk (imu_sensor.h)
  params.duration_s = 10.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  // A 0.5 deg/s gyro bias: the LQR rate loop tracks the biased gyro, so the vehicle rotates at
  // the bias until the ground-truth attitude loop cancels it, a small steady tilt.
  params.imu.gyro_bias_initial_B = Eigen::Vector3d(0.0087, -0.0087, 0.005);
  params.imu.accel_bias_initial_B = Eigen::Vector3d(0.05, -0.05, 0.1);
  params.SetSeed(11);
  SitlRunner runner(params, nullptr);
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  const SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  const double deviation_m = MaxDeviation(result, params.initial_state.p_WB);
  // "A few cm": tilt from a 0.5 deg/s bias against p_rp = 16.6 /s is ~0.03 deg, i.e. ~5 mm/s^2
  // of horizontal acceleration rejected by p_xy = 5 /s^2: ~1 mm; 3 cm leaves room for noise.
  EXPECT_LT(deviation_m, 0.03);
  // The noise must have reached the loop: deviation above the noise-free hover's.
  EXPECT_GT(deviation_m, 1e-5);
  EXPECT_EQ(result.imu.size(), 5000u);  // 500 Hz, delivered with 2 ms latency over 10 s
}

TEST(SitlRunner, WaypointStepConvergesAndReportsDone) {
  SitlRunnerParams params = test_support::QuietSitlParams(8.0);
  GroundTruthAutopilotParams autopilot_params;
  const Eigen::Vector3d goal(1.0, -0.5, 2.0);
  autopilot_params.waypoints.push_back(Waypoint{goal, 0.3, 1.0});
  autopilot_params.arrival_radius_m = 0.02;
  autopilot_params.finish_when_done = true;
  SitlRunner runner(params, nullptr);
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  const SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kAutopilotDone) << result.reason;
  // Done requires 1 s within 2 cm; with p = 5, d = 4 (damping ratio 0.9, settling ~2 s) this
  // takes ~3-4 s.
  EXPECT_LT(result.sim_time_s, 6.0);
  EXPECT_GT(result.sim_time_s, 1.0);
  const control::QuadState& last = result.trajectory.back();
  EXPECT_LT((last.p_WB - goal).norm(), 0.02);
  EXPECT_LT(last.v_W.norm(), 0.05);
  // Heading reached too: yaw of x_B.
  const Eigen::Vector3d x_B = last.q_WB * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(std::atan2(x_B.y(), x_B.x()), 0.3, 0.02);
}

struct CameraRunOutput {
  SitlResult result;
  std::vector<std::uint64_t> hashes;
};

CameraRunOutput RunWithCamera(std::uint64_t seed, const Scene& scene) {
  SitlRunnerParams params;  // noisy IMU
  params.duration_s = 1.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.0);
  SitlCamera camera = ForwardCamera(30.0);
  camera.drop_probability = 0.2;
  camera.effects.exposure_s = 0.004;
  camera.effects.motion_blur_subframes = 2;
  params.cameras.push_back(camera);
  params.SetSeed(seed);
  SitlRunner runner(params, &scene);
  GroundTruthAutopilotParams autopilot_params;
  autopilot_params.waypoints.push_back(Waypoint{Eigen::Vector3d(0.5, 0.2, 1.2), 0.0, 0.0});
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  CameraRunOutput out;
  SitlHooks hooks;
  hooks.on_frame = [&out](int, const CapturedFrame& frame, const control::QuadState&) {
    out.hashes.push_back(HashImage(frame.frame.image));
  };
  out.result = runner.Run(autopilot, hooks);
  return out;
}

TEST(SitlRunner, SameSeedGivesIdenticalTrajectoryAndImages) {
  const Scene scene = TexturedBoxScene();
  const CameraRunOutput a = RunWithCamera(5, scene);
  const CameraRunOutput b = RunWithCamera(5, scene);
  const CameraRunOutput c = RunWithCamera(6, scene);
  ASSERT_EQ(a.result.trajectory.size(), b.result.trajectory.size());
  for (size_t i = 0; i < a.result.trajectory.size(); ++i) {
    ASSERT_EQ(a.result.trajectory[i].p_WB, b.result.trajectory[i].p_WB) << "step " << i;
    ASSERT_EQ(a.result.trajectory[i].q_WB.coeffs(), b.result.trajectory[i].q_WB.coeffs());
  }
  ASSERT_FALSE(a.hashes.empty());
  EXPECT_EQ(a.hashes, b.hashes);
  // Another seed changes drops and pixel noise, so the image sequences differ.
  EXPECT_NE(a.hashes, c.hashes);
  // And the trajectory: different IMU noise on the flight controller's gyro.
  EXPECT_NE(a.result.trajectory.back().p_WB, c.result.trajectory.back().p_WB);
}

// Records what the autopilot receives and when (the time of the next Step after delivery).
class RecordingAutopilot : public GroundTruthAutopilot {
 public:
  using GroundTruthAutopilot::GroundTruthAutopilot;
  struct Arrival {
    double t_measured_s;
    double t_step_s;
    int index;
  };
  void OnFrame(const perception::Frame& frame) override {
    pending_frames_.push_back({frame.t_s, 0.0, frame.index});
  }
  void OnRange(const perception::RangeReading& reading) override {
    pending_ranges_.push_back({reading.t_s, 0.0, 0});
  }
  void OnImu(const perception::ImuSample& sample) override {
    pending_imu_.push_back({sample.t_s, 0.0, 0});
  }
  perception::AutopilotCommand Step(double t_s) override {
    Flush(t_s, &pending_frames_, &frames);
    Flush(t_s, &pending_ranges_, &ranges);
    Flush(t_s, &pending_imu_, &imu);
    return GroundTruthAutopilot::Step(t_s);
  }
  std::vector<Arrival> frames, ranges, imu;

 private:
  static void Flush(double t_s, std::vector<Arrival>* pending, std::vector<Arrival>* done) {
    for (Arrival a : *pending) {
      a.t_step_s = t_s;
      done->push_back(a);
    }
    pending->clear();
  }
  std::vector<Arrival> pending_frames_, pending_ranges_, pending_imu_;
};

TEST(SitlRunner, FramesAreDroppedAtTheConfiguredRate) {
  const Scene scene = TexturedBoxScene();
  SitlRunnerParams params = test_support::QuietSitlParams(10.0);
  SitlCamera camera = ForwardCamera(30.0);
  camera.model = std::make_shared<perception::PinholeCamera>(
      40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});  // drops, not pixels
  camera.drop_probability = 0.3;
  params.cameras.push_back(camera);
  params.SetSeed(3);
  SitlRunner runner(params, &scene);
  RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  int renders = 0;
  SitlHooks hooks;
  hooks.before_render = [&renders](double, const control::QuadState&) { ++renders; };
  const SitlResult result = runner.Run(autopilot, hooks);
  ASSERT_EQ(result.cameras.size(), 1u);
  const SitlCameraStats& stats = result.cameras[0];
  EXPECT_EQ(stats.frames_due, 301);  // 30 Hz over [0, 10] s inclusive
  EXPECT_EQ(stats.frames_due, stats.frames_dropped + stats.frames_delivered);
  // Binomial(301, 0.3): mean 90.3, sigma 7.95; 4 sigma keeps the seeded test far from the edge.
  EXPECT_NEAR(stats.frames_dropped, 0.3 * 301, 4.0 * 7.95);
  EXPECT_EQ(static_cast<int>(autopilot.frames.size()), stats.frames_delivered);
  EXPECT_EQ(renders, stats.frames_delivered);  // dropped frames are not rendered
  // Frame indices keep counting through drops: the gaps add up to the dropped count.
  int gaps = 0;
  for (size_t i = 1; i < autopilot.frames.size(); ++i) {
    gaps += autopilot.frames[i].index - autopilot.frames[i - 1].index - 1;
  }
  gaps += autopilot.frames.front().index + (stats.frames_due - 1 - autopilot.frames.back().index);
  EXPECT_EQ(gaps, stats.frames_dropped);
}

// An outage loses exactly the frames whose exposure ends inside it; the drop draws of the other
// frames are those of the same run without the outage (the same frames are dropped).
TEST(SitlRunner, OutageLosesTheFramesInsideItsWindowOnly) {
  const Scene scene = TexturedBoxScene();
  const auto run = [&scene](const std::vector<TimeWindow>& outages) {
    SitlRunnerParams params = test_support::QuietSitlParams(2.0);
    SitlCamera camera = ForwardCamera(30.0);
    camera.model = std::make_shared<perception::PinholeCamera>(
        40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});
    camera.drop_probability = 0.2;
    camera.outages = outages;
    params.cameras.push_back(camera);
    params.SetSeed(4);
    RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
    const SitlResult result = SitlRunner(params, &scene).Run(autopilot);
    std::vector<int> indices;
    for (const RecordingAutopilot::Arrival& frame : autopilot.frames)
      indices.push_back(frame.index);
    return std::make_pair(result.cameras.at(0), indices);
  };
  const auto [stats_free, indices_free] = run({});
  const auto [stats_out, indices_out] = run({TimeWindow{0.5, 1.0}});
  // Frame k ends its exposure at k / 30 s: k = 15 .. 29 lie in [0.5, 1.0).
  std::vector<int> expected;
  for (int k : indices_free) {
    if (k < 15 || k > 29) expected.push_back(k);
  }
  EXPECT_EQ(indices_out, expected);
  EXPECT_EQ(stats_out.frames_due, stats_free.frames_due);
  EXPECT_EQ(stats_out.frames_dropped + stats_out.frames_delivered, stats_out.frames_due);
  EXPECT_GT(stats_out.frames_dropped, stats_free.frames_dropped);
}

TEST(SitlRunner, OutageEndingBeforeItStartsIsRejected) {
  SitlRunnerParams params = test_support::QuietSitlParams(1.0);
  SitlCamera camera = ForwardCamera(30.0);
  camera.outages = {TimeWindow{1.0, 0.5}};
  params.cameras.push_back(camera);
  const Scene scene = TexturedBoxScene();
  try {
    SitlRunner runner(params, &scene);
    FAIL() << "an inverted outage window was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cameras.front.outages[0]"), std::string::npos)
        << e.what();
  }
}

// record_window_s: a long flight's records keep their last window (between one and two windows),
// the tail of the same flight with every record kept.
TEST(SitlRunner, RecordWindowKeepsTheLastWindowOfTheSameFlight) {
  SitlRunnerParams params = test_support::QuietSitlParams(6.0);
  params.trajectory_decimation = 5;
  GroundTruthAutopilot autopilot_all(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  const SitlResult all = SitlRunner(params, nullptr).Run(autopilot_all);
  params.record_window_s = 1.0;
  GroundTruthAutopilot autopilot_window(params.dynamics.vehicle,
                                        HoverAt(params.initial_state.p_WB));
  const SitlResult window = SitlRunner(params, nullptr).Run(autopilot_window);
  // The same flight: its last states agree to the bit.
  ASSERT_FALSE(window.trajectory.empty());
  EXPECT_EQ(window.trajectory.back().p_WB, all.trajectory.back().p_WB);
  EXPECT_EQ(window.trajectory.back().t_s, all.trajectory.back().t_s);
  const auto check = [](const auto& kept, const auto& every, const char* name) {
    ASSERT_FALSE(kept.empty()) << name;
    EXPECT_LT(kept.size(), every.size() / 2) << name;
    EXPECT_GE(kept.front().t_s, 6.0 - 2.0 - 1e-9) << name;
    EXPECT_LE(kept.front().t_s, 6.0 - 1.0 + 0.01) << name;
    // Exactly the tail of the full record.
    EXPECT_EQ(kept.back().t_s, every.back().t_s) << name;
    EXPECT_EQ(every[every.size() - kept.size()].t_s, kept.front().t_s) << name;
  };
  check(window.trajectory, all.trajectory, "trajectory");
  check(window.commands, all.commands, "commands");
  check(window.imu, all.imu, "imu");
  check(window.range, all.range, "range");
  params.record_window_s = -1.0;
  EXPECT_THROW(SitlRunner(params, nullptr), std::invalid_argument);
}

TEST(SitlRunner, TwoCamerasDeliverAtTheirOwnRatesTheirOwnViews) {
  // A forward camera at 30 Hz sees the box ahead; a downward one at 20 Hz sees only the ground.
  const Scene scene = TexturedBoxScene();
  SitlRunnerParams params = test_support::QuietSitlParams(1.0);
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.0);
  SitlCamera front = ForwardCamera(30.0);
  front.model = std::make_shared<perception::PinholeCamera>(
      40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});
  front.render.ground_truth = true;
  SitlCamera down = front;
  down.name = "down";
  down.rate_hz = 20.0;
  // C looking along -z_B: x_C = -y_B, y_C = -x_B, z_C = -z_B.
  down.T_BC.linear() << 0, -1, 0, -1, 0, 0, 0, 0, -1;
  params.cameras = {front, down};
  SitlRunner runner(params, &scene);
  RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  std::vector<std::vector<double>> stamps(2);
  std::vector<cv::Mat> ids(2);
  SitlHooks hooks;
  hooks.on_frame = [&](int camera_index, const CapturedFrame& frame, const control::QuadState&) {
    EXPECT_EQ(frame.frame.camera_id, camera_index);
    stamps[camera_index].push_back(frame.frame.t_s);
    if (ids[camera_index].empty()) ids[camera_index] = frame.object_id.clone();
  };
  const SitlResult result = runner.Run(autopilot, hooks);
  ASSERT_EQ(result.cameras.size(), 2u);
  EXPECT_EQ(result.cameras[0].frames_delivered, 31);  // 30 Hz over [0, 1] s inclusive
  EXPECT_EQ(result.cameras[1].frames_delivered, 21);  // 20 Hz
  ASSERT_EQ(stamps[0].size(), 31u);
  ASSERT_EQ(stamps[1].size(), 21u);
  for (size_t i = 1; i < stamps[0].size(); ++i) {
    EXPECT_NEAR(stamps[0][i] - stamps[0][i - 1], 1.0 / 30.0, 1e-3);  // on the 1 ms step grid
  }
  for (size_t i = 1; i < stamps[1].size(); ++i) {
    EXPECT_NEAR(stamps[1][i] - stamps[1][i - 1], 1.0 / 20.0, 1e-9);
  }
  EXPECT_EQ(static_cast<int>(autopilot.frames.size()), 31 + 21);
  // Each camera renders its own view: the box fills the forward view's centre, the downward
  // view is all ground.
  const int box = scene.FindId("box"), ground = scene.FindId("ground");
  EXPECT_EQ(ids[0].at<int>(15, 20), box);
  EXPECT_EQ(cv::countNonZero(ids[1] == ground), ids[1].rows * ids[1].cols);
}

TEST(SitlRunner, RangeSensorSeesABoxBelowAndLooksThroughIgnoredParts) {
  SitlRunnerParams params = test_support::QuietSitlParams(0.5);
  params.range.noise_sigma_m = 0.0;
  Scene scene;
  Eigen::Isometry3d T_WBox = Eigen::Isometry3d::Identity();
  T_WBox.translation() = Eigen::Vector3d(0.0, 0.0, 0.25);  // top at 0.5 m, 1 m below the vehicle
  scene.AddObject({"box", Box{Eigen::Vector3d(1.0, 1.0, 0.5)}, Material{}, T_WBox});
  Eigen::Isometry3d T_WShelf = Eigen::Isometry3d::Identity();
  T_WShelf.translation() = Eigen::Vector3d(0.0, 0.0, 1.2);  // 0.3 m below: a part to ignore
  scene.AddObject({"shelf", Box{Eigen::Vector3d(0.3, 0.3, 0.02)}, Material{}, T_WShelf});
  params.collision.ignored_objects = {"shelf"};
  SitlRunner runner(params, &scene);
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  const SitlResult result = runner.Run(autopilot);
  ASSERT_FALSE(result.range.empty());
  for (const perception::RangeReading& reading : result.range) {
    ASSERT_TRUE(reading.valid) << "t = " << reading.t_s;
    EXPECT_NEAR(reading.range_m, 1.0, 1e-3) << "t = " << reading.t_s;  // not 1.5 nor 0.29
  }
}

TEST(SitlRunner, LatencyDelaysDeliveryByTheConfiguredAmount) {
  const Scene scene = TexturedBoxScene();
  SitlRunnerParams params = test_support::QuietSitlParams(1.0);
  params.control_rate_hz = 1000.0;  // Step every dynamics step: arrival known to 1 ms
  params.range_latency_s = 0.02;
  params.imu.latency_s = 0.004;
  SitlCamera camera = ForwardCamera(30.0);
  camera.model = std::make_shared<perception::PinholeCamera>(
      40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});
  camera.latency_s = 0.05;
  params.cameras.push_back(camera);
  SitlRunner runner(params, &scene);
  RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  runner.Run(autopilot);
  const auto check = [](const std::vector<RecordingAutopilot::Arrival>& arrivals, double latency_s,
                        const char* what) {
    ASSERT_FALSE(arrivals.empty()) << what;
    for (const RecordingAutopilot::Arrival& a : arrivals) {
      // Delivered in the step at t_measured + latency, seen by the Step of that same step.
      EXPECT_NEAR(a.t_step_s - a.t_measured_s, latency_s, 1e-6) << what << " at " << a.t_measured_s;
    }
  };
  check(autopilot.frames, 0.05, "frames");  // exposure 0: stamp = end of exposure
  check(autopilot.ranges, 0.02, "range");
  check(autopilot.imu, 0.004, "imu");
  EXPECT_GT(autopilot.frames.size(), 25u);  // 30 Hz over 1 s minus those still in flight
}

TEST(SitlRunner, FlyingIntoAWallEndsWithContactOnTheWall) {
  Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(2.0, 0.0, 1.5);
  scene.AddObject({"wall", Box{Eigen::Vector3d(0.1, 4.0, 3.0)}, Material{}, T_WO});
  SitlRunnerParams params = test_support::QuietSitlParams(10.0);
  SitlRunner runner(params, &scene);
  // Waypoint behind the wall: the autopilot flies straight into its face at x = 1.95.
  RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(Eigen::Vector3d(4.0, 0.0, 1.5)));
  const SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kCollision) << result.reason;
  ASSERT_TRUE(result.collision.has_value());
  EXPECT_EQ(result.collision->object_name, "wall");
  // Contact on the face: rays stop on the surface (x = 1.95), within its extent.
  EXPECT_NEAR(result.collision->contact_p_W.x(), 1.95, 1e-6);
  EXPECT_LT(std::abs(result.collision->contact_p_W.y()), 2.0);
  // At ~1-2 m/s the vehicle moves ~2 mm per step: it is stopped within one step of the
  // first touch, so the nearest part (a propeller tip or the body) just reaches the face.
  const double reach_m = 0.178 + params.collision.propeller_radius_m;  // arm + propeller
  EXPECT_GT(result.trajectory.back().p_WB.x(), 1.95 - reach_m - 0.01);
  EXPECT_LT(result.trajectory.back().p_WB.x(), 1.95 - params.collision.body_radius_m * 0.9);
  EXPECT_NE(result.reason.find("wall"), std::string::npos);
}

TEST(SitlRunner, FlyingIntoTheGroundEndsTheRun) {
  SitlRunnerParams params = test_support::QuietSitlParams(10.0);
  params.initial_state.p_WB = Eigen::Vector3d(0.5, 0.0, 1.0);
  SitlRunner runner(params, nullptr);
  RecordingAutopilot autopilot(params.dynamics.vehicle, HoverAt(Eigen::Vector3d(0.5, 0.0, -1.0)));
  const SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kCollision) << result.reason;
  EXPECT_EQ(result.collision->object_name, "ground");
  EXPECT_DOUBLE_EQ(result.collision->contact_p_W.z(), 0.0);
  EXPECT_NEAR(result.collision->contact_p_W.x(), 0.5, 0.05);  // straight down
  // The body sphere touches first in level descent: its centre is one radius up.
  EXPECT_EQ(result.collision->part, "body");
  EXPECT_NEAR(result.trajectory.back().p_WB.z(), params.collision.body_radius_m, 0.01);
  EXPECT_LT(result.sim_time_s, 5.0);
}

// Rotor thrusts stepped at t = 0.5 s: the flight controller applies them command_latency_s later.
class ThrustStepAutopilot : public perception::Autopilot {
 public:
  std::string name() const override { return "thrust_step"; }
  perception::AutopilotCommand Step(double t_s) override {
    perception::AutopilotCommand command;
    command.kind = perception::AutopilotCommand::Kind::kRotorThrusts;
    // Near the hover thrust m g / 4 = 1.104 N, so the vehicle stays airborne.
    command.rotor_thrusts.thrust_N.setConstant(t_s < 0.5 - 1e-9 ? 1.10 : 1.15);
    return command;
  }
};

TEST(SitlRunner, CommandLatencyDelaysTheFlightControllerOutput) {
  for (const double latency_s : {0.0, 0.05}) {
    SitlRunnerParams params = test_support::QuietSitlParams(1.0);
    params.command_latency_s = latency_s;
    SitlRunner runner(params, nullptr);
    ThrustStepAutopilot autopilot;
    const SitlResult result = runner.Run(autopilot);
    double first_s = -1.0;
    for (const SitlCommandRecord& record : result.commands) {
      if (record.rotor_thrusts_N(0) > 1.125) {
        first_s = record.t_s;
        break;
      }
    }
    // Records carry the flight-controller output of the step before: the new thrust applied at
    // 0.5 s + latency shows in the next 100 Hz record.
    EXPECT_NEAR(first_s, 0.5 + latency_s + 0.01, 1e-6) << "latency " << latency_s;
  }
}

// Equal rotor thrusts: `before_N` until switch_s, `after_N` from then on.
class ConstantThrustAutopilot : public perception::Autopilot {
 public:
  ConstantThrustAutopilot(double before_N, double after_N, double switch_s)
      : before_N_(before_N), after_N_(after_N), switch_s_(switch_s) {}
  std::string name() const override { return "constant_thrust"; }
  perception::AutopilotCommand Step(double t_s) override {
    perception::AutopilotCommand command;
    command.kind = perception::AutopilotCommand::Kind::kRotorThrusts;
    command.rotor_thrusts.thrust_N.setConstant(t_s < switch_s_ - 1e-9 ? before_N_ : after_N_);
    return command;
  }

 private:
  double before_N_, after_N_, switch_s_;
};

// Ground contact on, landing gear 0.1 m (body sphere 0.08 m), ground at z = 0.
SitlRunnerParams GroundContactParams(double duration_s) {
  SitlRunnerParams params = test_support::QuietSitlParams(duration_s);
  params.dynamics.ground_contact_enabled = true;
  params.dynamics.landing_gear_height_m = 0.1;
  return params;
}

double HoverRotorThrust_N(const SitlRunnerParams& params) {
  return params.dynamics.vehicle.mass_kg * params.dynamics.vehicle.gravity_mps2 / 4.0;
}

TEST(SitlRunner, SoftLandingWithGroundContactRestsOnTheGear) {
  SitlRunnerParams params = GroundContactParams(2.0);
  // Hover thrust with d_z = 0: a steady 0.3 m/s descent from 0.4 m, touchdown at t = 1 s.
  params.initial_state.p_WB = Eigen::Vector3d(0.5, -0.5, 0.4);
  params.initial_state.v_W = Eigen::Vector3d(0.0, 0.0, -0.3);
  const double hover_N = HoverRotorThrust_N(params);
  ConstantThrustAutopilot autopilot(hover_N, hover_N, 0.0);
  const SitlResult result = SitlRunner(params, nullptr).Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  EXPECT_FALSE(result.collision.has_value());
  for (const control::QuadState& state : result.trajectory) {
    // On the gear from the touchdown on (RK4 moves a 1 ms step by 0.3 mm).
    if (state.t_s > 1.0 + 1e-3) {
      EXPECT_NEAR(state.p_WB.z(), 0.1, 1e-9) << "t = " << state.t_s;
    }
    EXPECT_GE(state.p_WB.z(), 0.1 - 1e-12);
  }
  EXPECT_NEAR(result.trajectory.back().v_W.norm(), 0.0, 1e-9);
  EXPECT_TRUE(result.trajectory.back().p_WB.head<2>().isApprox(Eigen::Vector2d(0.5, -0.5)));
  // Without ground contact the same descent is a crash of the body sphere.
  params.dynamics.ground_contact_enabled = false;
  const SitlResult crash = SitlRunner(params, nullptr).Run(autopilot);
  ASSERT_EQ(crash.outcome, SitlResult::Outcome::kCollision);
  EXPECT_EQ(crash.collision->part, "body");
}

TEST(SitlRunner, HardTouchdownWithGroundContactIsAGroundCollision) {
  SitlRunnerParams params = GroundContactParams(2.0);
  params.initial_state.p_WB = Eigen::Vector3d(0.5, -0.5, 1.0);
  params.initial_state.v_W = Eigen::Vector3d(0.0, 0.0, -3.0);  // 3 m/s > the 1 m/s limit
  const double hover_N = HoverRotorThrust_N(params);
  ConstantThrustAutopilot autopilot(hover_N, hover_N, 0.0);
  const SitlResult result = SitlRunner(params, nullptr).Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kCollision) << result.reason;
  EXPECT_EQ(result.collision->object_name, "ground");
  EXPECT_EQ(result.collision->part, "landing gear");
  EXPECT_EQ(result.reason, "collision: landing gear with 'ground'");
  EXPECT_TRUE(result.collision->contact_p_W.isApprox(Eigen::Vector3d(0.5, -0.5, 0.0)));
  EXPECT_NEAR(result.sim_time_s, 0.3, 2e-3);  // 0.9 m at 3 m/s
}

TEST(SitlRunner, TakesOffFromTheGroundWithGroundContact) {
  SitlRunnerParams params = GroundContactParams(1.5);
  params.start_hovering = false;  // motors idle on the ground
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 0.1);
  const double hover_N = HoverRotorThrust_N(params);
  // Half the weight for 0.5 s (it stays on the ground), then 30 % more than the weight.
  ConstantThrustAutopilot autopilot(0.5 * hover_N, 1.3 * hover_N, 0.5);
  const SitlResult result = SitlRunner(params, nullptr).Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  for (const control::QuadState& state : result.trajectory) {
    if (state.t_s <= 0.5) {
      EXPECT_NEAR(state.p_WB.z(), 0.1, 1e-12) << "t = " << state.t_s;
    }
  }
  // 0.3 g up for ~1 s (minus the rotor spin-up): ~1.4 m; at least well off the ground.
  EXPECT_GT(result.trajectory.back().p_WB.z(), 1.0);
  EXPECT_GT(result.trajectory.back().v_W.z(), 2.0);
}

TEST(SitlRunner, RejectsLandingGearInsideTheBodySphere) {
  SitlRunnerParams params = GroundContactParams(1.0);
  params.dynamics.landing_gear_height_m = 0.05;  // < body_radius_m = 0.08
  EXPECT_THROW(SitlRunner(params, nullptr), std::invalid_argument);
}

// A push is applied through the disturbances: the hover autopilot is knocked away, then returns.
TEST(SitlRunner, PushDisturbsTheHoverWhichRecovers) {
  SitlRunnerParams params = test_support::QuietSitlParams(5.0);
  params.disturbances.pushes.push_back(Push{1.0, Eigen::Vector3d(0.45, 0.0, 0.0)});  // 1 m/s
  SitlRunner runner(params, nullptr);
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, HoverAt(params.initial_state.p_WB));
  const SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  double max_x = 0.0;
  for (const control::QuadState& s : result.trajectory) {
    if (s.t_s < 1.0) {
      EXPECT_LT(s.p_WB.norm() - 1.5, 1e-6);  // undisturbed before the push
    }
    max_x = std::max(max_x, s.p_WB.x());
  }
  // 1 m/s against p = 5, d = 4 (damping 0.9, omega_n 2.2 /s): peak ~ v / omega_n * 0.6 ~ 0.2 m.
  EXPECT_GT(max_x, 0.1);
  EXPECT_LT(max_x, 0.4);
  // Four seconds (~9 / omega_n) later it is back within 1 cm.
  EXPECT_LT((result.trajectory.back().p_WB - params.initial_state.p_WB).norm(), 0.01);
}

// A world-fixed camera sees the same (noise-free) images whatever the vehicle does; a body
// camera does not.
TEST(SitlRunner, WorldFixedCameraIgnoresTheVehiclePose) {
  const Scene scene = TexturedBoxScene();
  const auto hashes = [&scene](const Eigen::Vector3d& goal, bool fixed) {
    SitlRunnerParams params = test_support::QuietSitlParams(0.3);
    SitlCamera camera = ForwardCamera(30.0);
    camera.effects = CameraEffectsParams();  // no noise
    if (fixed)
      camera.T_WC_fixed = Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 1.0)) * camera.T_BC;
    params.cameras.push_back(camera);
    SitlRunner runner(params, &scene);
    GroundTruthAutopilot autopilot(params.dynamics.vehicle, HoverAt(goal));
    std::vector<std::uint64_t> out;
    SitlHooks hooks;
    hooks.on_frame = [&out](int, const CapturedFrame& frame, const control::QuadState&) {
      out.push_back(HashImage(frame.frame.image));
    };
    runner.Run(autopilot, hooks);
    return out;
  };
  const Eigen::Vector3d left(0.0, 1.0, 1.5), right(0.0, -1.0, 1.5);
  EXPECT_EQ(hashes(left, true), hashes(right, true));
  const std::vector<std::uint64_t> body_left = hashes(left, false);
  const std::vector<std::uint64_t> body_right = hashes(right, false);
  ASSERT_EQ(body_left.size(), body_right.size());
  EXPECT_EQ(body_left.front(), body_right.front());  // same start
  EXPECT_NE(body_left.back(), body_right.back());    // moved apart by then
}

TEST(SitlRunner, RejectsInconsistentParameters) {
  SitlRunnerParams params;
  params.dynamics_rate_hz = 400.0;  // below the 1 kHz flight controller
  EXPECT_THROW(SitlRunner(params, nullptr), std::invalid_argument);
  params = SitlRunnerParams();
  params.cameras.push_back(ForwardCamera(30.0));
  params.cameras.back().drop_probability = 1.0;
  const Scene scene = TexturedBoxScene();
  EXPECT_THROW(SitlRunner(params, &scene), std::invalid_argument);
  params.cameras.back().drop_probability = 0.0;
  EXPECT_THROW(SitlRunner(params, nullptr), std::invalid_argument);  // cameras need a scene
}

}  // namespace
}  // namespace aperture::sim
