// `aperture run` end to end on generated image folders: outputs, frame counts, bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// `count` PNG frames of a moving, blurring square so image_quality has something to measure.
void WriteSequence(const fs::path& folder, int count) {
  fs::create_directories(folder);
  for (int i = 0; i < count; ++i) {
    cv::Mat image(120, 160, CV_8UC1, cv::Scalar(40));
    cv::rectangle(image, cv::Rect(10 + 5 * i, 30, 50, 50), cv::Scalar(220), cv::FILLED);
    cv::GaussianBlur(image, image, cv::Size(0, 0), 0.5 + i);
    cv::imwrite((folder / ("frame" + std::to_string(i) + ".png")).string(), image);
  }
}

void CorruptFile(const fs::path& path) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << "this is not a png";
}

TEST(RunCommand, ImageQualityOnAFolderWritesSummaryCsvAndReport) {
  TempFolder temp("run");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  const fs::path out = fs::path(temp.path()) / "out";
  WriteSequence(sequence, 6);

  const CommandResult result = RunAperture("run --source " + sequence.string() +
                                           " --fps 20 --frontends image_quality --out " +
                                           out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["frames"], 6);
  EXPECT_EQ(summary["skipped_frames"], 0);
  EXPECT_EQ(summary["timing"]["nodes"]["image_quality"]["count"], 6);
  EXPECT_GT(summary["timing"]["nodes"]["image_quality"]["median_s"].get<double>(), 0.0);
  // The blur grows every frame, so the sharpness falls: min at the last frame, max at the first.
  const auto& sharpness = summary["metrics"]["image_quality.sharpness_laplacian_var"];
  EXPECT_LT(sharpness["min"].get<double>(), sharpness["max"].get<double>());
  EXPECT_EQ(CountLines(out / "frames.csv"), 1u + 6u);  // header + one row per frame
  std::ifstream report(out / "report.html");
  const std::string html((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
}

TEST(RunCommand, VideoFlagWritesTheOverlayVideo) {
  TempFolder temp("run-video");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  const fs::path out = fs::path(temp.path()) / "out";
  WriteSequence(sequence, 4);
  const CommandResult result = RunAperture("run --source " + sequence.string() +
                                           " --fps 10 --video --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  ASSERT_TRUE(summary["outputs"].contains("video"));
  EXPECT_TRUE(fs::exists(out / summary["outputs"]["video"].get<std::string>()));
}

TEST(RunCommand, CorruptFrameFailsNamingTheFileUnlessSkipped) {
  TempFolder temp("run-corrupt");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  WriteSequence(sequence, 5);
  CorruptFile(sequence / "frame3.png");

  const fs::path strict_out = fs::path(temp.path()) / "strict";
  const CommandResult strict =
      RunAperture("run --source " + sequence.string() + " --fps 20 --out " + strict_out.string());
  EXPECT_NE(strict.exit_code, 0);
  EXPECT_NE(strict.output.find("frame3.png"), std::string::npos) << strict.output;
  const nlohmann::json failed = ReadJson(strict_out / "summary.json");
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_NE(failed["error"].get<std::string>().find("frame3.png"), std::string::npos);

  const fs::path skip_out = fs::path(temp.path()) / "skip";
  const CommandResult skipping = RunAperture("run --source " + sequence.string() +
                                             " --fps 20 --skip-bad-frames --out " +
                                             skip_out.string());
  ASSERT_EQ(skipping.exit_code, 0) << skipping.output;
  EXPECT_NE(skipping.output.find("frame3.png"), std::string::npos);  // the warning
  const nlohmann::json summary = ReadJson(skip_out / "summary.json");
  EXPECT_EQ(summary["frames"], 4);
  EXPECT_EQ(summary["skipped_frames"], 1);
  EXPECT_NE(summary["skipped"][0]["item"].get<std::string>().find("frame3.png"),
            std::string::npos);
}

TEST(RunCommand, EmptyOrMissingFolderFailsWithAClearMessage) {
  TempFolder temp("run-empty");
  const fs::path empty = fs::path(temp.path()) / "empty";
  fs::create_directories(empty);
  const CommandResult result = RunAperture("run --source " + empty.string() + " --fps 20 --out " +
                                           (fs::path(temp.path()) / "out").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(empty.string()), std::string::npos) << result.output;
  const CommandResult missing = RunAperture("run --source " + temp.path() + "/nope --out " +
                                            (fs::path(temp.path()) / "out2").string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("nope"), std::string::npos) << missing.output;
}

TEST(RunCommand, UnknownConfigKeyAndUnknownFrontEndAreRejected) {
  TempFolder temp("run-config");
  const fs::path sequence = fs::path(temp.path()) / "seq";
  WriteSequence(sequence, 2);
  const std::string base = "run --source " + sequence.string() + " --fps 20 --out " +
                           (fs::path(temp.path()) / "out").string();
  const CommandResult typo = RunAperture(base + " --set image_quality.histogram_bin=8");
  EXPECT_NE(typo.exit_code, 0);
  EXPECT_NE(typo.output.find("image_quality.histogram_bin"), std::string::npos) << typo.output;

  const fs::path config = fs::path(temp.path()) / "params.yaml";
  std::ofstream(config) << "image_quality:\n  histogram_bins: 8\nimage_qualty:\n  x: 1\n";
  const CommandResult file_typo = RunAperture(base + " --config " + config.string());
  EXPECT_NE(file_typo.exit_code, 0);
  // The message names the file, the line and the key.
  EXPECT_NE(file_typo.output.find("params.yaml:3"), std::string::npos) << file_typo.output;
  EXPECT_NE(file_typo.output.find("image_qualty"), std::string::npos) << file_typo.output;

  const CommandResult unknown = RunAperture(base + " --frontends image_quality,warp_drive");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("warp_drive"), std::string::npos) << unknown.output;
}

TEST(RunCommand, BadFlagValuesExitWithTwo) {
  EXPECT_EQ(RunAperture("run --source x --out y --fps -3").exit_code, 2);
  EXPECT_EQ(RunAperture("run --out y").exit_code, 2);  // --source is required
}

}  // namespace
}  // namespace aperture::apps::testing
