// `aperture render` end to end: the dataset replays through `aperture run`, its depth and id-mask
// PNGs match ray-cast ground truth (mask ids named by summary.json), the ground-truth files have
// one entry per frame, each --trajectory kind moves the camera as kinematic_trajectory.h says,
// and objects.csv holds the configured object poses (the gap) and the body-attached ones (LEDs).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "perception/camera/calibration_io.h"
#include "perception/camera/optical_axes.h"
#include "sim/scenario/kinematic_trajectory.h"
#include "sim/scenario/scenario.h"
#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// Non-comment lines of a text file.
std::vector<std::string> DataLines(const fs::path& path) {
  std::ifstream file(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

Eigen::Isometry3d ParseTumPose(const std::string& line) {
  std::istringstream in(line);
  double t, x, y, z, qx, qy, qz, qw;
  in >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

// One row of objects.csv: t,name,tx,ty,tz,qx,qy,qz,qw (T_WO).
struct ObjectPose {
  double t_s;
  std::string name;
  Eigen::Isometry3d T_WO;
};

std::vector<ObjectPose> ReadObjectPoses(const fs::path& path) {
  std::vector<std::string> lines = DataLines(path);
  std::vector<ObjectPose> rows;
  if (lines.empty()) return rows;
  lines.erase(lines.begin());  // header
  for (std::string line : lines) {
    const std::size_t first = line.find(','), second = line.find(',', first + 1);
    const std::string name = line.substr(first + 1, second - first - 1);
    line = line.substr(0, first) + line.substr(second);  // t,tx,...,qw: TUM numbers
    std::replace(line.begin(), line.end(), ',', ' ');
    rows.push_back({std::stod(line), name, ParseTumPose(line)});
  }
  return rows;
}

// T_WO of `name` in every frame, in frame order.
std::vector<Eigen::Isometry3d> PosesOf(const std::vector<ObjectPose>& rows,
                                       const std::string& name) {
  std::vector<Eigen::Isometry3d> poses;
  for (const ObjectPose& row : rows) {
    if (row.name == name) poses.push_back(row.T_WO);
  }
  return poses;
}

std::vector<Eigen::Isometry3d> CameraPoses(const fs::path& dataset) {
  std::vector<Eigen::Isometry3d> poses;
  for (const std::string& line : DataLines(dataset / "groundtruth.txt")) {
    poses.push_back(ParseTumPose(line));
  }
  return poses;
}

std::size_t CountPngs(const fs::path& folder) {
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    count += entry.path().extension() == ".png" ? 1 : 0;
  }
  return count;
}

// Poses read back from text written with 15-17 significant digits agree to ~1e-15 relative;
// 1e-9 m / 1e-9 rad leaves room for the quaternion round trip.
constexpr double kPoseTolerance = 1e-9;

// Angle of the rotation between R_a and R_b [rad].
double AngleBetween(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(R_a.transpose() * R_b)).angle();
}

void ExpectPoseNear(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected,
                    const std::string& what) {
  EXPECT_LT((actual.translation() - expected.translation()).norm(), kPoseTolerance) << what;
  EXPECT_LT(AngleBetween(actual.linear(), expected.linear()), kPoseTolerance) << what;
}

// A small dataset: `arguments` (scenario, flags, --set items) plus the output folder; expects
// `frames` entries in every per-frame output.
class RenderTrajectory : public ::testing::Test {
 protected:
  // 94 x 60 front camera without supersampling: a few ms per frame.
  static constexpr const char* kTinyFront =
      " --set cameras.front.width=94 --set cameras.front.height=60"
      " --set cameras.front.supersampling=1";

  fs::path Render(const std::string& name, const std::string& arguments, int frames) {
    const fs::path dataset = fs::path(temp_.path()) / name;
    const CommandResult result = RunAperture("render " + arguments + " --frames " +
                                             std::to_string(frames) + " --out " + dataset.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(CountPngs(dataset / "images"), static_cast<std::size_t>(frames));
    EXPECT_EQ(CountPngs(dataset / "depth"), static_cast<std::size_t>(frames));
    EXPECT_EQ(CountPngs(dataset / "masks"), static_cast<std::size_t>(frames));
    EXPECT_EQ(DataLines(dataset / "images" / "times.txt").size(), static_cast<std::size_t>(frames));
    EXPECT_EQ(DataLines(dataset / "groundtruth.txt").size(), static_cast<std::size_t>(frames));
    return dataset;
  }

  TempFolder temp_{"render_trajectory"};
};

// The scene as `aperture render` builds it from the built-in `name` and --set items.
sim::Scenario BuiltScenario(const std::string& name, const std::vector<std::string>& set_items) {
  return sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig(name, {}, set_items)));
}

TEST_F(RenderTrajectory, HoverKeepsTheStartPoseAndTheGapSitsWhereConfigured) {
  const fs::path dataset = Render("hover",
                                  std::string("gap --trajectory hover --set gap.roll_deg=20 "
                                              "--set 'gap.center_W=[4.5, 0.2, 1.4]'") +
                                      kTinyFront,
                                  5);
  const sim::Scenario scenario = BuiltScenario("gap", {});
  const Eigen::Isometry3d T_WC_start = scenario.render_camera().T_WC(scenario.T_WB_start());
  for (const Eigen::Isometry3d& T_WC : CameraPoses(dataset)) {
    ExpectPoseNear(T_WC, T_WC_start, "hover camera pose");
  }
  // scenario_params.h GapParams: G at the opening centre, z_G = x_W, x_G = -y_W, y_G = -z_W at
  // zero angles, roll about x_W.
  const Eigen::Matrix3d R_W_G0 = perception::OpticalAxesAlongX();
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  T_WG.linear() = Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) * R_W_G0;
  T_WG.translation() = Eigen::Vector3d(4.5, 0.2, 1.4);
  const std::vector<Eigen::Isometry3d> gap =
      PosesOf(ReadObjectPoses(dataset / "objects.csv"), "gap");
  ASSERT_EQ(gap.size(), 5u);
  for (const Eigen::Isometry3d& T_WO : gap) ExpectPoseNear(T_WO, T_WG, "gap pose");
}

TEST_F(RenderTrajectory, CircleKeepsTheDistanceToTheAxisAndTurnsTheCameraWithTheArc) {
  const fs::path dataset =
      Render("circle",
             std::string("gap --trajectory circle --set 'trajectory.center_p_m=[2.0, 1.0, 0.0]' "
                         "--set trajectory.arc_deg=90") +
                 kTinyFront,
             7);
  const std::vector<Eigen::Isometry3d> poses = CameraPoses(dataset);
  ASSERT_EQ(poses.size(), 7u);
  const Eigen::Vector2d axis_W(2.0, 1.0);
  const double radius_m = (poses[0].translation().head<2>() - axis_W).norm();
  EXPECT_GT(radius_m, 2.0);  // the camera starts 0.1 m ahead of the body at (0, 0)
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Isometry3d& T_WC = poses[k];
    EXPECT_NEAR((T_WC.translation().head<2>() - axis_W).norm(), radius_m, kPoseTolerance) << k;
    EXPECT_NEAR(T_WC.translation().z(), poses[0].translation().z(), kPoseTolerance) << k;
    // The camera yaws with the arc: R_WC(k) = Rz(90 deg * k / 6) R_WC(0).
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.5 * M_PI * k / 6.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT(AngleBetween(T_WC.linear(), turn * poses[0].linear()), kPoseTolerance) << k;
  }
}

TEST_F(RenderTrajectory, ScanMovesAlongTheLineWithALateralSinusoid) {
  // gap's built-in trajectory: end_p_m [4, 0, 1.5], amplitude_m 0.4, cycles 1; start at the
  // origin facing +x_W (body y = y_W), camera 0.1 m ahead of the body.
  const fs::path dataset = Render("scan", std::string("gap --trajectory scan") + kTinyFront, 9);
  const std::vector<Eigen::Isometry3d> poses = CameraPoses(dataset);
  ASSERT_EQ(poses.size(), 9u);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double s = k / 8.0;
    const Eigen::Vector3d expected_p_WC(0.1 + 4.0 * s, 0.4 * std::sin(2.0 * M_PI * s), 1.5);
    EXPECT_LT((poses[k].translation() - expected_p_WC).norm(), kPoseTolerance) << k;
    EXPECT_LT(AngleBetween(poses[k].linear(), poses[0].linear()), kPoseTolerance) << k;
  }
  EXPECT_NEAR(poses[2].translation().y(), 0.4, kPoseTolerance);  // the sinusoid's crest
}

TEST_F(RenderTrajectory, RandomWanderIsSeededBoundedAndReturnsToTheStart) {
  const std::string arguments = std::string("gap --trajectory random") + kTinyFront;
  const std::vector<Eigen::Isometry3d> seed1 =
      CameraPoses(Render("random1", arguments + " --seed 1", 9));
  const std::vector<Eigen::Isometry3d> seed2 =
      CameraPoses(Render("random2", arguments + " --seed 2", 9));
  ASSERT_EQ(seed1.size(), 9u);
  ASSERT_EQ(seed2.size(), 9u);
  const sim::Scenario scenario = BuiltScenario("gap", {});
  const sim::ScenarioCamera& camera = scenario.render_camera();
  const double amplitude_m = scenario.params().trajectory.amplitude_m;
  const Eigen::Isometry3d T_WC_start = camera.T_WC(scenario.T_WB_start());
  double largest_seed_difference_m = 0.0;
  for (const auto* poses : {&seed1, &seed2}) {
    // Each axis: sinusoids of 1, 2 and 3 periods started at zero, so the run ends where it began;
    // weights sum to 1, so the body stays within 2 amplitude_m of the start per axis.
    ExpectPoseNear(poses->front(), T_WC_start, "random start");
    ExpectPoseNear(poses->back(), T_WC_start, "random end");
    double largest_offset_m = 0.0;
    for (const Eigen::Isometry3d& T_WC : *poses) {
      const Eigen::Vector3d offset_W =
          (T_WC * camera.T_BC->inverse()).translation() - scenario.T_WB_start().translation();
      EXPECT_LE(offset_W.cwiseAbs().maxCoeff(), 2.0 * amplitude_m);
      largest_offset_m = std::max(largest_offset_m, offset_W.norm());
    }
    EXPECT_GT(largest_offset_m, 0.25 * amplitude_m);  // it does wander
  }
  for (std::size_t k = 0; k < seed1.size(); ++k) {
    largest_seed_difference_m = std::max(largest_seed_difference_m,
                                         (seed1[k].translation() - seed2[k].translation()).norm());
  }
  EXPECT_GT(largest_seed_difference_m, 0.05);  // the seed picks the phases
}

TEST_F(RenderTrajectory, LedTargetAndLedsFollowTheVehiclePose) {
  // `led` renders the static ground camera; the LED target and its LEDs ride on T_WB(t).
  const fs::path dataset =
      Render("led",
             "led --set cameras.ground.width=94 --set cameras.ground.height=60 "
             "--set cameras.ground.supersampling=1",
             5);
  const sim::Scenario scenario = BuiltScenario("led", {});
  const sim::ScenarioParams& params = scenario.params();
  const sim::KinematicTrajectory trajectory(params.trajectory, scenario.T_WB_start(), params.seed);
  const std::vector<ObjectPose> rows = ReadObjectPoses(dataset / "objects.csv");
  const std::vector<Eigen::Isometry3d> target = PosesOf(rows, "led_target");
  ASSERT_EQ(target.size(), 5u);
  for (std::size_t k = 0; k < target.size(); ++k) {
    const Eigen::Isometry3d T_WB = trajectory.T_WB(k / 4.0);
    ExpectPoseNear(target[k], T_WB, "led_target at frame " + std::to_string(k));
    for (std::size_t i = 0; i < params.led.leds_B.size(); ++i) {
      const std::vector<Eigen::Isometry3d> led = PosesOf(rows, "led" + std::to_string(i));
      ASSERT_EQ(led.size(), 5u);
      EXPECT_LT((led[k].translation() - T_WB * params.led.leds_B[i]).norm(), kPoseTolerance);
    }
  }
  // The world-mounted camera does not move.
  for (const Eigen::Isometry3d& T_WC : CameraPoses(dataset)) {
    ExpectPoseNear(T_WC, *scenario.render_camera().T_WC_fixed, "ground camera pose");
  }
  EXPECT_GT((target[2].translation() - target[0].translation()).norm(), 0.01);
}

class RenderCommand : public ::testing::Test {
 protected:
  // One 20-frame gap dataset shared by the tests (supersampling 1 keeps it fast).
  static void SetUpTestSuite() {
    temp_ = new TempFolder("render");
    dataset_ = fs::path(temp_->path()) / "gap";
    render_result_ = new CommandResult(RunAperture(
        "render gap --frames 20 --set cameras.front.supersampling=1 --out " + dataset_.string()));
  }
  static void TearDownTestSuite() {
    delete render_result_;
    delete temp_;
  }

  static TempFolder* temp_;
  static fs::path dataset_;
  static CommandResult* render_result_;
};

TempFolder* RenderCommand::temp_ = nullptr;
fs::path RenderCommand::dataset_;
CommandResult* RenderCommand::render_result_ = nullptr;

TEST_F(RenderCommand, DatasetReplaysThroughRun) {
  ASSERT_EQ(render_result_->exit_code, 0) << render_result_->output;
  const nlohmann::json summary = ReadJson(dataset_ / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["frames"], 20);
  EXPECT_GT(summary["timing"]["frames_per_s"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(dataset_ / "report.html"));

  const fs::path out = fs::path(temp_->path()) / "run";
  // The dataset folder itself is a source: its frames are found in images/.
  const CommandResult run = RunAperture("run --source " + dataset_.string() + " --calib " +
                                        (dataset_ / "calib.yaml").string() +
                                        " --frontends image_quality --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json run_summary = ReadJson(out / "summary.json");
  EXPECT_EQ(run_summary["frames"], 20);
  // Times came from the dataset's times.txt (50 Hz camera), not from a guessed rate.
  EXPECT_NE(run_summary["inputs"]["source_description"].get<std::string>().find("times.txt"),
            std::string::npos);
}

TEST_F(RenderCommand, GroundTruthFilesHaveOneEntryPerFrame) {
  ASSERT_EQ(render_result_->exit_code, 0) << render_result_->output;
  EXPECT_EQ(DataLines(dataset_ / "groundtruth.txt").size(), 20u);
  EXPECT_EQ(DataLines(dataset_ / "images" / "times.txt").size(), 20u);
  const std::size_t object_count = ReadJson(dataset_ / "summary.json")["objects"].size();
  EXPECT_EQ(DataLines(dataset_ / "objects.csv").size(), 1u + 20u * object_count);  // + header
  // The line trajectory approaches the gap: 5 m to 1 m from it (camera 0.1 m ahead of the body).
  const auto first = ParseTumPose(DataLines(dataset_ / "groundtruth.txt").front());
  const auto last = ParseTumPose(DataLines(dataset_ / "groundtruth.txt").back());
  EXPECT_NEAR(first.translation().x(), 0.1, 1e-9);
  EXPECT_NEAR(last.translation().x(), 4.1, 1e-9);
}

TEST_F(RenderCommand, DepthAndMaskPngsMatchRayCastGroundTruth) {
  ASSERT_EQ(render_result_->exit_code, 0) << render_result_->output;
  // Mask ids name the objects summary.json lists (0 = sky).
  std::map<int, std::string> names{{0, "sky"}};
  const nlohmann::json summary = ReadJson(dataset_ / "summary.json");
  for (const nlohmann::json& object : summary["objects"]) {
    names[object["id"].get<int>()] = object["name"].get<std::string>();
  }
  const perception::CameraCalibration calib =
      perception::LoadCameraCalibration((dataset_ / "calib.yaml").string());
  // The scene as rendered (default seed); the dataset's own pose and calibration files.
  const sim::Scenario scenario =
      sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig("gap")));
  const std::vector<std::string> poses = DataLines(dataset_ / "groundtruth.txt");
  for (const int frame : {0, 13}) {
    std::ostringstream name;
    name << std::setw(6) << std::setfill('0') << frame << ".png";
    const cv::Mat depth =
        cv::imread((dataset_ / "depth" / name.str()).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_16UC1);
    const cv::Mat mask =
        cv::imread((dataset_ / "masks" / name.str()).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_16UC1);
    const Eigen::Isometry3d T_WC = ParseTumPose(poses[frame]);
    int checked = 0;
    for (int v = 10; v < depth.rows; v += 47) {
      for (int u = 10; u < depth.cols; u += 61) {
        const Eigen::Vector3d ray_C = calib.camera->Unproject(Eigen::Vector2d(u, v));
        const auto hit = scenario.scene().Intersect(T_WC.translation(), T_WC.linear() * ray_C);
        const int mm = depth.at<std::uint16_t>(v, u);
        const int id = mask.at<std::uint16_t>(v, u);
        ASSERT_EQ(names.count(id), 1u) << "mask id " << id << " at pixel " << u << "," << v;
        EXPECT_EQ(names[id], hit ? scenario.scene().object(hit->object_id).name : "sky")
            << "pixel " << u << "," << v;
        if (!hit || ray_C.z() <= 0.0) {
          EXPECT_EQ(mm, 0) << "pixel " << u << "," << v;
          continue;
        }
        // Rounding to mm (0.5) + float depth and TUM pose text precision (<< 0.1 mm).
        EXPECT_NEAR(mm, 1000.0 * hit->t_m * ray_C.z(), 1.0) << "pixel " << u << "," << v;
        ++checked;
      }
    }
    EXPECT_GT(checked, 50);
  }
  // Every id in every mask is a listed object; the gap being flown at is seen.
  std::set<int> seen;
  for (const auto& entry : fs::directory_iterator(dataset_ / "masks")) {
    const cv::Mat mask = cv::imread(entry.path().string(), cv::IMREAD_UNCHANGED);
    for (auto it = mask.begin<std::uint16_t>(); it != mask.end<std::uint16_t>(); ++it) {
      seen.insert(*it);
    }
  }
  for (const int id : seen) EXPECT_EQ(names.count(id), 1u) << "mask id " << id;
  EXPECT_EQ(seen.count(scenario.scene().object("gap").id), 1u);
}

}  // namespace
}  // namespace aperture::apps::testing
