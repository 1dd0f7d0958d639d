// `aperture train mono_depth` and front end `mono_depth` end to end: train on a rendered forest
// folder, score a held-out one (Table I keys in summary.json), then replay the held-out folder
// through `aperture run`: one 16-bit depth PNG per frame of the frame's size, Table I errors
// per frame from the depth beside the images, and clear errors for gray frames and bad data.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// A small colour forest dataset (160x120 keeps the test fast; 4 px patches at 80 px work width).
void RenderForest(const std::string& out, int seed, int frames) {
  const CommandResult render =
      RunAperture("render forest --trajectory scan --frames " + std::to_string(frames) +
                  " --seed " + std::to_string(seed) +
                  " --set cameras.front.color=true --set cameras.front.width=160 "
                  "--set cameras.front.height=120 --set cameras.front.supersampling=1 --out " +
                  out);
  ASSERT_EQ(render.exit_code, 0) << render.output;
}

TEST(MonoDepthCommand, TrainsScoresAndReplaysThroughRun) {
  TempFolder folder("mono_depth_cli");
  const std::string train = folder.path() + "/train", held_out = folder.path() + "/held_out";
  RenderForest(train, 3, 6);
  RenderForest(held_out, 4, 3);
  const std::string model_dir = folder.path() + "/model";
  const CommandResult trained =
      RunAperture("train mono_depth --data " + train + " --eval " + held_out +
                  " --set work_width_px=80 --set patch_px=4 --out " + model_dir);
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  const nlohmann::json summary = ReadJson(model_dir + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["training"]["frames"], 6);
  EXPECT_EQ(summary["training"]["patches"], 6 * 20 * 15);
  EXPECT_EQ(summary["eval"]["frames"], 3);
  const double e_ln = summary["eval"]["e_ln"];
  EXPECT_TRUE(std::isfinite(e_ln) && e_ln > 0.0);
  ASSERT_TRUE(fs::exists(model_dir + "/mono_depth.model"));

  const std::string run = folder.path() + "/run";
  const CommandResult replay = RunAperture("run --source " + held_out +
                                           " --color --frontends mono_depth --set "
                                           "mono_depth.model=" +
                                           model_dir + "/mono_depth.model --out " + run);
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/mono_depth/%06d.png", i);
    const cv::Mat depth = cv::imread(run + name, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_16UC1) << name;
    EXPECT_EQ(depth.size(), cv::Size(160, 120));
  }
  // The run scores the same frames with the same model: its per-frame E_ln (frames.csv column
  // mono_depth.e_ln, mean in summary.json) equals train's per-frame evaluation (eval.csv, col. 3).
  std::ifstream eval_csv(model_dir + "/eval.csv");
  std::string line;
  std::getline(eval_csv, line);  // header
  double sum = 0.0;
  int rows = 0;
  while (std::getline(eval_csv, line)) {
    std::stringstream cells(line);
    std::string cell;
    for (int column = 0; column < 3; ++column) std::getline(cells, cell, ',');
    sum += std::stod(cell);
    ++rows;
  }
  ASSERT_EQ(rows, 3);
  const nlohmann::json run_summary = ReadJson(run + "/summary.json");
  EXPECT_NEAR(double(run_summary["metrics"]["mono_depth.e_ln"]["mean"]), sum / rows, 1e-9);
}

TEST(MonoDepthCommand, GrayFramesAndFoldersWithoutDepthAreClearErrors) {
  TempFolder folder("mono_depth_cli_errors");
  const std::string data = folder.path() + "/data";
  RenderForest(data, 5, 1);
  const CommandResult gray = RunAperture("run --source " + data + " --frontends mono_depth --out " +
                                         folder.path() + "/gray");
  EXPECT_EQ(gray.exit_code, 1);
  EXPECT_NE(gray.output.find("--color"), std::string::npos) << gray.output;
  const CommandResult no_depth = RunAperture("train mono_depth --data " + folder.path() +
                                             " --out " + folder.path() + "/model");
  EXPECT_EQ(no_depth.exit_code, 1);
  EXPECT_NE(no_depth.output.find("images/ and depth/"), std::string::npos) << no_depth.output;
}

}  // namespace
}  // namespace aperture::apps::testing
