// Values checked like files (issue 18, item 1), end to end: every bad value on the command line
// is a clear error naming the option or key with exit code 2 (a usage mistake), numbers must be
// finite and in range, one seed rule for every command, and a reused --out folder is refused
// unless --overwrite, which clears what the earlier run wrote.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// Tiny frames: the runs below only check how values are taken.
const std::string kValuesTinyFront = " --set cameras.front.width=32 --set cameras.front.height=24 ";

bool OutputHas(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ValuesCli, SetCannotInventACameraAndNamesTheKnownOnes) {
  TempFolder temp("values_camera");
  const CommandResult typo =
      RunAperture("sim gap --set cameras.frnt.rate_hz=30 --out " + temp.path() + "/a");
  EXPECT_EQ(typo.exit_code, 2) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "unknown camera 'frnt'")) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "known: front")) << typo.output;
  // The led scenario's camera is `ground`: a front camera is no more known there.
  const CommandResult led =
      RunAperture("sim led --set cameras.front.rate_hz=30 --out " + temp.path() + "/b");
  EXPECT_EQ(led.exit_code, 2) << led.output;
  EXPECT_TRUE(OutputHas(led.output, "known: ground")) << led.output;
}

TEST(ValuesCli, NonFiniteAndHugeNumbersAreUsageErrorsWithReadableMessages) {
  TempFolder temp("values_numbers");
  for (const std::string value : {".nan", "1e308", "-.inf"}) {
    const CommandResult result = RunAperture("sim gap --set gap.roll_deg=" + value + " --out " +
                                             temp.path() + "/set" + std::to_string(value.size()));
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_TRUE(OutputHas(result.output, "--set gap.roll_deg=" + value)) << result.output;
    EXPECT_TRUE(OutputHas(result.output, "[-360, 360] degrees")) << result.output;
    EXPECT_FALSE(OutputHas(result.output, "0000000000")) << result.output;  // no 309 digits
  }
  for (const std::string value : {"nan", "inf", "1e308", "0", "-1"}) {
    const CommandResult result =
        RunAperture("sim gap --duration " + value + " --out " + temp.path() + "/duration");
    EXPECT_EQ(result.exit_code, 2) << value << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, "--duration")) << result.output;
    EXPECT_TRUE(OutputHas(result.output, "(0, 864000]")) << result.output;
    EXPECT_FALSE(OutputHas(result.output, "SitlRunnerParams")) << result.output;
  }
}

TEST(ValuesCli, FpsHasOneRuleForEveryBadValue) {
  TempFolder temp("values_fps");
  for (const std::string value : {"inf", "1e-300", "nan", "0", "-30", "1e308"}) {
    const CommandResult result =
        RunAperture("run --source " + temp.path() + " --fps " + value +
                    " --frontends image_quality --out " + temp.path() + "/out");
    EXPECT_EQ(result.exit_code, 2) << value << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, "--fps")) << result.output;
    EXPECT_TRUE(OutputHas(result.output, "[0.001, 10000]")) << result.output;
  }
}

TEST(ValuesCli, OneSeedRuleForEveryCommand) {
  TempFolder temp("values_seed");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sim gap", "-1"},      {"sim gap", "18446744073709551616"},
      {"sim gap", "1e3"},     {"sim gap", "0x10"},
      {"render gap", "-1"},   {"render gap", "99999999999999999999"},
      {"bench led", "-1"},    {"bench led", "99999999999999999999"},
      {"bench control", "-1"}};
  for (const auto& [command, seed] : cases) {
    const CommandResult result =
        RunAperture(command + " --seed " + seed + " --out " + temp.path() + "/seed");
    EXPECT_EQ(result.exit_code, 2) << command << " --seed " << seed << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, "18446744073709551615")) << result.output;
    EXPECT_FALSE(fs::exists(temp.path() + "/seed")) << "nothing runs on a bad seed";
  }
  // The largest seed is taken as it is and recorded exactly (a JSON integer, not a double).
  const fs::path out = fs::path(temp.path()) / "max";
  const CommandResult result = RunAperture("render gap --frames 1 --seed 18446744073709551615" +
                                           kValuesTinyFront + "--out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["inputs"]["seed"].get<std::uint64_t>(), 18446744073709551615ull);
  EXPECT_EQ(summary["config"]["seed"].get<std::uint64_t>(), 18446744073709551615ull);
}

TEST(ValuesCli, ReusedOutFolderIsRefusedUnlessOverwriteWhichClearsTheEarlierRun) {
  TempFolder temp("values_out");
  const fs::path out = fs::path(temp.path()) / "out";
  ASSERT_EQ(
      RunAperture("render gap --frames 3" + kValuesTinyFront + "--out " + out.string()).exit_code,
      0);
  ASSERT_TRUE(fs::exists(out / "images" / "000002.png"));
  std::ofstream(out / "notes.txt") << "the user's own file";

  const CommandResult refused =
      RunAperture("render gap --frames 1" + kValuesTinyFront + "--out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_TRUE(OutputHas(refused.output, "--overwrite")) << refused.output;
  EXPECT_TRUE(fs::exists(out / "images" / "000002.png"));  // nothing touched

  const CommandResult replaced =
      RunAperture("render gap --frames 1 --overwrite" + kValuesTinyFront + "--out " + out.string());
  ASSERT_EQ(replaced.exit_code, 0) << replaced.output;
  EXPECT_TRUE(fs::exists(out / "images" / "000000.png"));
  EXPECT_FALSE(fs::exists(out / "images" / "000001.png"));  // the earlier run's frames are gone
  EXPECT_FALSE(fs::exists(out / "images" / "000002.png"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));  // not the earlier run's: kept
  std::ifstream times(out / "images" / "times.txt");
  int lines = 0;
  for (std::string line; std::getline(times, line);) ++lines;
  EXPECT_EQ(lines, 1);
}

TEST(ValuesCli, RenderChecksItsLedFileAndRecordsTheLedsItRendered) {
  TempFolder temp("values_leds");
  const fs::path leds = fs::path(temp.path()) / "leds.yaml";
  // The built-in layout with two LEDs moved: valid, and different from what the defaults say.
  std::ofstream(leds) << "leds: [[0, 0.1, 0], [0.1, 0.01, 0], [0.02, -0.09, -0.03], "
                         "[-0.09, -0.04, 0], [-0.04, 0.04, -0.09]]\n";
  const std::string tiny_ground = " --set cameras.ground.width=32 --set cameras.ground.height=24 ";
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result =
      RunAperture("render led --frames 1 --set led.config=" + leds.string() + tiny_ground +
                  "--out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json rendered = ReadJson(out / "summary.json")["config"]["led"]["leds"];
  ASSERT_EQ(rendered.size(), 5u);
  EXPECT_DOUBLE_EQ(rendered[0][1].get<double>(), 0.1);  // the file's, not the built-in 0.105
  EXPECT_DOUBLE_EQ(rendered[4][2].get<double>(), -0.09);

  const fs::path coplanar = fs::path(temp.path()) / "coplanar.yaml";
  std::ofstream(coplanar) << "leds: [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0.1, 0.1, 0]]\n";
  const CommandResult bad =
      RunAperture("render led --frames 1 --set led.config=" + coplanar.string() + tiny_ground +
                  "--out " + temp.path() + "/bad");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;  // the file's content is bad data
  EXPECT_TRUE(OutputHas(bad.output, "coplanar")) << bad.output;
}

TEST(ValuesCli, RenderRefusesADatasetLargerThanTheDisk) {
  TempFolder temp("values_frames");
  const CommandResult result =
      RunAperture("render gap --frames 1000000000 --out " + temp.path() + "/out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(OutputHas(result.output, "1000000000 frames of 752x480 need up to")) << result.output;
  EXPECT_TRUE(OutputHas(result.output, "GB")) << result.output;
  EXPECT_FALSE(fs::exists(fs::path(temp.path()) / "out" / "images" / "000000.png"));
}

TEST(ValuesCli, DeviceOrFifoIsNamedAsSuchInsteadOfMissingOrHanging) {
  TempFolder temp("values_fifo");
  const std::string fifo = temp.path() + "/pipe.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const CommandResult config = RunAperture("sim gap --config " + fifo + " --out " + temp.path() +
                                           "/a");  // would wait forever for a writer
  EXPECT_EQ(config.exit_code, 1) << config.output;
  EXPECT_TRUE(OutputHas(config.output, "config file '" + fifo + "' is not a regular file"))
      << config.output;
  const CommandResult source =
      RunAperture("run --source /dev/null --fps 30 --out " + temp.path() + "/b");
  EXPECT_EQ(source.exit_code, 1) << source.output;
  EXPECT_TRUE(OutputHas(source.output, "'/dev/null' is not a regular file")) << source.output;
  EXPECT_FALSE(OutputHas(source.output, "does not exist")) << source.output;
}

TEST(ValuesCli, BenchAloneListsTheBenchesAndSimHelpSaysOutIsRequired) {
  const CommandResult bench = RunAperture("bench");
  EXPECT_EQ(bench.exit_code, 2);
  for (const std::string name :
       {"control", "gap", "gapflyt", "led", "merge", "mononav", "ts2p", "tags"}) {
    EXPECT_TRUE(OutputHas(bench.output, "aperture bench " + name + ":")) << bench.output;
  }
  const CommandResult help = RunAperture("sim --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(OutputHas(help.output, "REQUIRED with a scenario NAME")) << help.output;
}

}  // namespace
}  // namespace aperture::apps::testing
