// TS²P end to end through the CLI: `aperture bench ts2p --quick` scores against the rendered
// truth, and `aperture render gapflyt --trajectory scan` followed by
// `aperture run --frontends ts2p,gap_tracker` writes openings that overlap the true opening.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchTs2pCommand, QuickRunDetectsEveryShape) {
  TempFolder out("bench_ts2p");
  const CommandResult run = RunAperture("bench ts2p --quick --seed 2 --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  ASSERT_EQ(summary["table_ii"].size(), 1u);
  const nlohmann::json& row = summary["table_ii"][0];
  EXPECT_EQ(row["name"], "dis_medium");
  EXPECT_EQ(row["trials"], 5);
  // One trial per shape scored against the id masks: at least four of the five detected
  // (lambda_D >= 0.75; the small star is the weakest case, docs/results/ts2p.md), few gap pixels
  // missed and almost no wall pixels called opening on the detected ones.
  EXPECT_GE(row["dr"].get<double>(), 0.8);
  EXPECT_LE(row["afn"].get<double>(), 0.2);
  EXPECT_LE(row["afp"].get<double>(), 0.01);
  EXPECT_GT(row["time_ms"]["flow_mean"].get<double>(), 0.0);
  EXPECT_EQ(summary["tracking"]["tracked"], 1);
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/report.html"));
  EXPECT_EQ(CountLines(out.path() + "/trials.csv"), 6u);
}

class Ts2pRunTest : public ::testing::TestWithParam<std::string> {};

TEST_P(Ts2pRunTest, OpeningsOverlapTheTrueOpening) {
  TempFolder data("ts2p_scan_" + GetParam());
  TempFolder out("ts2p_run_" + GetParam());
  // 576 x 384 as the acceptance; 18 frames hold two detections at stack 4, stride 2.
  const CommandResult render = RunAperture(
      "render gapflyt --trajectory scan --frames 18 --set gapflyt.shape=" + GetParam() +
      " --set cameras.front.width=576 --set cameras.front.height=384 --out " + data.path());
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const CommandResult run =
      RunAperture("run --source " + data.path() + " --calib " + data.path() +
                  "/calib.yaml --frontends ts2p,gap_tracker --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // G: the background wall seen through the hole (the scan's openings sit high enough that no
  // ground shows through them; the ground in front of the wall at the image bottom is not G).
  int background_id = -1;
  const nlohmann::json render_summary = ReadJson(data.path() + "/summary.json");
  for (const auto& object : render_summary["objects"]) {
    if (object["name"] == "background") background_id = object["id"].get<int>();
  }
  ASSERT_GT(background_id, 0);
  int openings = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out.path() + "/openings")) {
    const std::string index = entry.path().stem().string();
    const cv::Mat opening = cv::imread(entry.path().string(), cv::IMREAD_UNCHANGED);
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.png", std::stoi(index));
    const cv::Mat ids = cv::imread(data.path() + "/masks/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(opening.type(), CV_8UC1);
    ASSERT_EQ(ids.size(), opening.size());
    const cv::Mat truth = ids == background_id;
    const double g = cv::countNonZero(truth);
    const double hit = cv::countNonZero(truth & (opening != 0));
    // Issue 13 acceptance: >= 0.75 for every shape, the star included (0.92-0.99 measured on
    // these scans, docs/results/ts2p.md): 0.85 so that a partial regression fails too.
    EXPECT_GE(hit / g, 0.85) << "frame " << index;
    ++openings;
  }
  EXPECT_GE(openings, 2);
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(CountLines(out.path() + "/ts2p.csv"), static_cast<std::size_t>(openings) + 1);
  EXPECT_EQ(CountLines(out.path() + "/gap_tracker.csv"), 19u);
}

INSTANTIATE_TEST_SUITE_P(FiveShapes, Ts2pRunTest,
                         ::testing::Values("ellipse", "polygon", "triangle", "notched", "star"));

}  // namespace
}  // namespace aperture::apps::testing
