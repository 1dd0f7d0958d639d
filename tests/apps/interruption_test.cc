// Ctrl-C and SIGTERM during `run`, `sim`, `render` and `bench` (output/interruption.h), sent for
// real to the built binary once its outputs show progress: the process exits with 128 + the
// signal, summary.json says "interrupted" with the counts so far, every CSV holds complete rows
// that match those counts, the video opens with its frames, nothing is left under a temporary
// name. And a source that fails after frames ends `run` as "failed" with the same guarantee.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// Generous: these runs take seconds, the timeouts only keep a broken build from hanging ctest.
constexpr double kTimeoutS = 120.0;

// The rows of a CSV file after its header; fails the test unless every line is complete: as many
// fields as the header, each a number or text, the file ending with a newline.
std::vector<std::vector<std::string>> CsvRows(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(file)), {});
  EXPECT_FALSE(text.empty()) << path;
  EXPECT_EQ(text.back(), '\n') << path << " ends mid-row";
  std::istringstream lines(text);
  std::vector<std::vector<std::string>> rows;
  std::size_t columns = 0;
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    if (columns == 0) {
      columns = fields.size();
      continue;
    }
    EXPECT_EQ(fields.size(), columns) << path << " row " << rows.size() + 1 << ": " << line;
    rows.push_back(fields);
  }
  return rows;
}

// Frames cv::VideoCapture decodes from `path`.
int DecodedFrames(const fs::path& path) {
  cv::VideoCapture video(path.string());
  EXPECT_TRUE(video.isOpened()) << path;
  int frames = 0;
  for (cv::Mat frame; video.read(frame) && !frame.empty();) ++frames;
  return frames;
}

// Files of the folder still under a temporary name ("*.tmp", "*.partial.*").
std::vector<std::string> TemporaryFiles(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.find(".partial.") != std::string::npos) {
      names.push_back(name);
    }
  }
  return names;
}

std::size_t CountFiles(const fs::path& folder, const std::string& extension) {
  std::size_t count = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    count += entry.path().extension() == extension;
  }
  return count;
}

// `count` frames for an image folder: symlinks to one 320x240 noise image beside the folder (fast
// to make, as slow to process as distinct images).
void WriteSymlinkedSequence(const fs::path& folder, int count) {
  fs::create_directories(folder);
  cv::Mat image(240, 320, CV_8UC1);
  cv::randu(image, 0, 255);
  const fs::path source = folder.parent_path() / "noise.png";
  cv::imwrite(source.string(), image);
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", i);
    fs::create_symlink(source, folder / name);
  }
}

TEST(Interruption, CtrlCDuringRunKeepsEveryFrameSoFar) {
  TempFolder temp("interrupt_run");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  const fs::path out = fs::path(temp.path()) / "out";
  constexpr int kFrames = 5000;
  WriteSymlinkedSequence(sequence, kFrames);
  ApertureProcess run({"run", "--source", sequence.string(), "--fps", "30", "--frontends",
                       "image_quality", "--video", "--out", out.string()});
  // Both appear with the first frame, under their temporary names.
  ASSERT_TRUE(run.WaitUntil(
      [&] { return fs::exists(out / "frames.csv.tmp") && fs::exists(out / "overlay.partial.mp4"); },
      kTimeoutS))
      << run.output();
  run.Signal(SIGINT);
  ASSERT_EQ(run.Wait(kTimeoutS), 130) << run.output();

  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["signal"], "SIGINT");
  const int frames = summary["frames"].get<int>();
  EXPECT_GE(frames, 1);
  EXPECT_LT(frames, kFrames);
  const auto rows = CsvRows(out / "frames.csv");
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(frames));
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(std::stoi(rows[i][1]), int(i));
  ASSERT_EQ(summary["outputs"]["video"], "overlay.mp4");
  EXPECT_EQ(DecodedFrames(out / "overlay.mp4"), frames);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_EQ(TemporaryFiles(out), std::vector<std::string>());
}

// A source that fails in the middle (a camera that disconnects; here a corrupt file, which the
// image folder reports the same way: an error from Next()) ends the run as "failed", exit 1,
// with the outputs of the frames before it complete.
TEST(Interruption, SourceFailingAfterFramesFailsTheRunWithTheFramesSoFar) {
  TempFolder temp("interrupt_source");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  const fs::path out = fs::path(temp.path()) / "out";
  WriteSymlinkedSequence(sequence, 8);
  fs::remove(sequence / "000005.png");
  std::ofstream(sequence / "000005.png") << "this is not a png";
  const CommandResult result =
      RunAperture("run --source " + sequence.string() + " --fps 30 --video --out " + out.string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("000005.png"), std::string::npos) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_NE(summary["error"].get<std::string>().find("000005.png"), std::string::npos);
  EXPECT_NE(summary["error"].get<std::string>().find("after 5 frames"), std::string::npos);
  EXPECT_EQ(summary["frames"], 5);
  EXPECT_EQ(CsvRows(out / "frames.csv").size(), 5u);
  EXPECT_EQ(DecodedFrames(out / summary["outputs"]["video"].get<std::string>()), 5);
  EXPECT_EQ(TemporaryFiles(out), std::vector<std::string>());
}

TEST(Interruption, SigtermDuringSimWritesTheFlightSoFar) {
  TempFolder temp("interrupt_sim");
  const fs::path out = fs::path(temp.path()) / "out";
  ApertureProcess sim({"sim", "gap", "--duration", "3600", "--set", "cameras.front.width=94",
                       "--set", "cameras.front.height=60", "--out", out.string()});
  // The video file appears when the encoder opens it with the first frame; a few more video
  // frames queued (report key frames) make the flight long enough to show in every file.
  ASSERT_TRUE(sim.WaitUntil([&] { return fs::exists(out / "sim.partial.mp4"); }, kTimeoutS))
      << sim.output();
  sim.Signal(SIGTERM);
  ASSERT_EQ(sim.Wait(kTimeoutS), 143) << sim.output();

  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["signal"], "SIGTERM");
  EXPECT_EQ(summary["outcome"], "stopped");
  const double sim_time_s = summary["sim_time_s"].get<double>();
  EXPECT_GT(sim_time_s, 0.0);
  EXPECT_LT(sim_time_s, 3600.0);
  const nlohmann::json& rows = summary["rows"];
  EXPECT_EQ(CsvRows(out / "trajectory.csv").size(), rows["trajectory"].get<std::size_t>());
  EXPECT_EQ(CsvRows(out / "commands.csv").size(), rows["commands"].get<std::size_t>());
  EXPECT_EQ(CsvRows(out / "imu.csv").size(), rows["imu"].get<std::size_t>());
  // 200 Hz ground truth from t = 0, the last row at the stop.
  EXPECT_GE(rows["trajectory"].get<double>(), 200.0 * sim_time_s);
  const auto trajectory = CsvRows(out / "trajectory.csv");
  ASSERT_FALSE(trajectory.empty());
  EXPECT_NEAR(std::stod(trajectory.back()[0]), sim_time_s, 0.005 + 1e-9);
  const int video_frames = summary["video"]["frames"].get<int>();
  EXPECT_GE(video_frames, 1);
  ASSERT_EQ(summary["outputs"]["video"], "sim.mp4");
  EXPECT_EQ(DecodedFrames(out / "sim.mp4"), video_frames);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_EQ(TemporaryFiles(out), std::vector<std::string>());
}

TEST(Interruption, CtrlCDuringRenderListsExactlyTheImagesWritten) {
  TempFolder temp("interrupt_render");
  const fs::path out = fs::path(temp.path()) / "out";
  ApertureProcess render({"render", "gap", "--frames", "5000", "--set", "cameras.front.width=94",
                          "--set", "cameras.front.height=60", "--set",
                          "cameras.front.supersampling=1", "--out", out.string()});
  ASSERT_TRUE(
      render.WaitUntil([&] { return fs::exists(out / "images" / "000003.png"); }, kTimeoutS))
      << render.output();
  render.Signal(SIGINT);
  ASSERT_EQ(render.Wait(kTimeoutS), 130) << render.output();

  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  const std::size_t frames = summary["frames"].get<std::size_t>();
  EXPECT_GE(frames, 4u);
  EXPECT_LT(frames, 5000u);
  EXPECT_EQ(summary["frames_planned"], 5000);
  EXPECT_EQ(CountFiles(out / "images", ".png"), frames);
  EXPECT_EQ(CountFiles(out / "depth", ".png"), frames);
  EXPECT_EQ(CountFiles(out / "masks", ".png"), frames);
  EXPECT_EQ(CountLines(out / "images" / "times.txt"), frames);
  EXPECT_EQ(CountLines(out / "groundtruth.txt"), frames + 1);  // its comment line
  const std::size_t objects = summary["objects"].size();
  EXPECT_EQ(CsvRows(out / "objects.csv").size(), frames * objects);
  // The dataset replays: `run` reads every image with the times of times.txt.
  const CommandResult replay = RunAperture("run --source " + (out / "images").string() + " --out " +
                                           (fs::path(temp.path()) / "replay").string());
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_EQ(ReadJson(fs::path(temp.path()) / "replay" / "summary.json")["frames"], frames);
  EXPECT_EQ(TemporaryFiles(out), std::vector<std::string>());
}

// Trials of the ground-truth autopilot (no camera) take a fraction of a second; one thread keeps
// them in order. The trial in flight at the signal finishes; no further trial starts.
TEST(Interruption, CtrlCDuringBenchKeepsTheFinishedTrials) {
  TempFolder temp("interrupt_bench");
  const fs::path out = fs::path(temp.path()) / "out";
  constexpr int kTrials = 1000;
  ApertureProcess bench({"bench", "gap", "--trials", std::to_string(kTrials), "--autopilot",
                         "ground_truth", "--duration", "6", "--threads", "1", "--out",
                         out.string()});
  // The progress bar ("gap trials [###...]  2/1000 ...") on the pseudo-terminal.
  const std::regex progress(R"(\b([0-9]+)/1000\b)");
  ASSERT_TRUE(bench.WaitUntil(
      [&] {
        const std::string& text = bench.output();
        int done = 0;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), progress);
             it != std::sregex_iterator(); ++it) {
          done = std::max(done, std::stoi((*it)[1]));
        }
        return done >= 2;
      },
      kTimeoutS))
      << bench.output();
  bench.Signal(SIGINT);
  ASSERT_EQ(bench.Wait(kTimeoutS), 130) << bench.output();

  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  const int completed = summary["trials_completed"].get<int>();
  EXPECT_GE(completed, 2);
  EXPECT_LT(completed, kTrials);
  EXPECT_EQ(summary["run"]["trials"], kTrials);
  EXPECT_EQ(summary["cost"]["trials"], completed);
  std::ifstream cbor(out / summary["records"].get<std::string>(), std::ios::binary);
  const nlohmann::json records = nlohmann::json::from_cbor(cbor);
  ASSERT_EQ(records.size(), static_cast<std::size_t>(completed));
  for (int k = 0; k < completed; ++k) EXPECT_EQ(records[k]["trial"], k);
  EXPECT_FALSE(fs::exists(out / "trials.csv"));  // no figures from a part of the run
  EXPECT_EQ(TemporaryFiles(out), std::vector<std::string>());
}

}  // namespace
}  // namespace aperture::apps::testing
