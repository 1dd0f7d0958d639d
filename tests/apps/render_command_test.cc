// `aperture render` end to end: the dataset replays through `aperture run`, its depth PNGs match
// ray-cast ground truth, and the ground-truth files have one entry per frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "perception/camera/calibration_io.h"
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
  const CommandResult run = RunAperture("run --source " + dataset_.string() +
                                        " --calib " + (dataset_ / "calib.yaml").string() +
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

TEST_F(RenderCommand, DepthPngMatchesRayCastGroundTruth) {
  ASSERT_EQ(render_result_->exit_code, 0) << render_result_->output;
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
    const Eigen::Isometry3d T_WC = ParseTumPose(poses[frame]);
    int checked = 0;
    for (int v = 10; v < depth.rows; v += 47) {
      for (int u = 10; u < depth.cols; u += 61) {
        const Eigen::Vector3d ray_C = calib.camera->Unproject(Eigen::Vector2d(u, v));
        const auto hit = scenario.scene().Intersect(T_WC.translation(), T_WC.linear() * ray_C);
        const int mm = depth.at<std::uint16_t>(v, u);
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
}

}  // namespace
}  // namespace aperture::apps::testing
