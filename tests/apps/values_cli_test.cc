// Values checked like files (issue 18, item 1), end to end: every bad value on the command line
// is a clear error naming the option or key with exit code 2 (a usage mistake), numbers must be
// finite and in range, one seed rule for every command, and a reused --out folder is refused
// unless --overwrite, which clears what the earlier run wrote.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
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

TEST(ValuesCli, SetDeclaresAnObjectOnlyByItsShapeAndATypoListsTheKnownObjects) {
  TempFolder temp("values_objects");
  const std::string render = "render gap --frames 1" + kValuesTinyFront;
  // No object is called crat: a typo, not a new 1 m box.
  const CommandResult typo =
      RunAperture(render + "--set objects.crat.pose.p_m=[1,0,0] --out " + temp.path() + "/a");
  EXPECT_EQ(typo.exit_code, 2) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "unknown object 'crat'")) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "known: (none)")) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "--set objects.crat.shape=")) << typo.output;
  // crate is declared by its shape; crat beside it is still a typo, named with the known crate.
  const std::string crate = "--set objects.crate.shape=box ";
  const CommandResult beside =
      RunAperture(render + crate + "--set objects.crat.radius_m=1 --out " + temp.path() + "/b");
  EXPECT_EQ(beside.exit_code, 2) << beside.output;
  EXPECT_TRUE(OutputHas(beside.output, "known: crate")) << beside.output;
  // Declared, then changed: rendered and recorded.
  const fs::path out = fs::path(temp.path()) / "c";
  const CommandResult declared =
      RunAperture(render + crate + "--set objects.crate.pose.p_m=[3,0,1.5] --out " + out.string());
  ASSERT_EQ(declared.exit_code, 0) << declared.output;
  const nlohmann::json object = ReadJson(out / "summary.json")["config"]["objects"]["crate"];
  EXPECT_EQ(object["shape"], "box");
  EXPECT_DOUBLE_EQ(object["pose"]["p_m"][0].get<double>(), 3.0);
  // The rendered camera is named among the known ones too.
  const CommandResult camera =
      RunAperture(render + "--set trajectory.camera=frnt --out " + temp.path() + "/d");
  EXPECT_EQ(camera.exit_code, 2) << camera.output;
  EXPECT_TRUE(OutputHas(camera.output, "known: front")) << camera.output;
}

// A struct of the code followed by a field ("GapMissionParams.hover_s", "TraverseParameters:
// max_evaluations") in a message meant for the user.
bool NamesAnInternalIdentifier(const std::string& text) {
  static const std::regex kStructField(R"(\b[A-Z][a-z0-9]+([A-Z][a-z0-9]*)+(\.|: )[a-z_])");
  return std::regex_search(text, kStructField);
}

TEST(ValuesCli, ValidationErrorsNameTheKeyAndItemNeverAStructOfTheCode) {
  TempFolder temp("values_names");
  // (--set item, the key the message names): checks of sections, nested sections, the camera's
  // effects and the assembled simulation.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"mission.hover_s=-1", "mission.hover_s"},
      {"mission.detector.canny_low=-1", "mission.detector.canny_low"},
      {"mission.filter.history_duration_s=-1", "mission.filter.history_duration_s"},
      {"mission.traverse.max_evaluations=0", "mission.traverse.max_evaluations"},
      {"mission.approach.limits.min_thrust_mps2=100", "mission.approach.limits.max_thrust_mps2"},
      {"collision.sphere_rays=0", "collision.sphere_rays"},
      {"dynamics.vehicle.mass_kg=0", "dynamics.vehicle.mass_kg"},
      {"imu.rate_hz=0", "imu.rate_hz"},
      {"range.max_range_m=0.1", "range.max_range_m"},
      {"cameras.front.gain=-1", "cameras.front.gain"},
      {"cameras.front.width=100000", "cameras.front.width"},
      {"sitl.control_rate_hz=0", "sitl.control_rate_hz"},
      {"cameras.front.rate_hz=1e6", "cameras.front.rate_hz"}};
  for (const auto& [item, key] : cases) {
    const CommandResult result =
        RunAperture("sim gap --duration 0.1 --set " + item + " --out " + temp.path() + "/out");
    EXPECT_EQ(result.exit_code, 2) << item << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, "--set " + item)) << result.output;
    EXPECT_TRUE(OutputHas(result.output, key)) << result.output;
    EXPECT_FALSE(NamesAnInternalIdentifier(result.output)) << result.output;
  }
  // The same check from a file: bad data (exit 1) at its line and column.
  const std::string config = temp.path() + "/mission.yaml";
  std::ofstream(config) << "mission:\n  hover_s: -1\n";
  const CommandResult file =
      RunAperture("sim gap --config " + config + " --out " + temp.path() + "/file");
  EXPECT_EQ(file.exit_code, 1) << file.output;
  EXPECT_TRUE(OutputHas(file.output, config + ":2:12: mission.hover_s = -1")) << file.output;
}

TEST(ValuesCli, CountOptionsAreIntegersWithReadableBounds) {
  TempFolder temp("values_counts");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render gap --frames 0", "'0' is not an integer >= 1"},
      {"run --source " + temp.path() + " --fps 30 --max-frames -1", "--max-frames"},
      {"sim gap --video-every 99999999999", "'99999999999' is not an integer >= 1"},
      {"sim gap --chase-every 0", "--chase-every"},
      {"sim gap --chase-height 1e9", "in [16, 2160]"},
      {"bench led --threads -1", "in [0, 4096]"},
      {"bench gapflyt --width 0", "in [32, 8192]"},
      {"bench gap --motion-blur-subframes 1000", "in [1, 64]"}};
  for (const auto& [command, expected] : cases) {
    const CommandResult result = RunAperture(command + " --out " + temp.path() + "/out");
    EXPECT_EQ(result.exit_code, 2) << command << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, expected)) << command << ": " << result.output;
    EXPECT_FALSE(OutputHas(result.output, "0000000000")) << result.output;  // no 309 digits
    EXPECT_FALSE(fs::exists(temp.path() + "/out")) << command;
  }
}

TEST(ValuesCli, AMissingOptionTheInputNeedsIsAUsageError) {
  TempFolder temp("values_missing");
  const fs::path data = fs::path(temp.path()) / "data";
  ASSERT_EQ(
      RunAperture("render gap --frames 2" + kValuesTinyFront + "--out " + data.string()).exit_code,
      0);
  const std::string frames = (data / "images").string();
  fs::remove(data / "images" / "times.txt");
  const CommandResult fps = RunAperture("run --source " + frames + " --out " + temp.path() + "/a");
  EXPECT_EQ(fps.exit_code, 2) << fps.output;
  EXPECT_TRUE(OutputHas(fps.output, "pass --fps")) << fps.output;
  const std::string run = "run --source " + frames + " --fps 30 ";
  const CommandResult calib = RunAperture(run + "--frontends apriltag --out " + temp.path() + "/b");
  EXPECT_EQ(calib.exit_code, 2) << calib.output;
  EXPECT_TRUE(OutputHas(calib.output, "pass --calib")) << calib.output;

  const std::string camchain = temp.path() + "/camchain.yaml";
  std::ofstream file(camchain);
  for (const std::string camera : {"cam0", "cam1"}) {
    file << camera << ":\n  camera_model: pinhole\n  intrinsics: [30, 30, 16, 12]\n"
         << "  distortion_model: radtan\n  distortion_coeffs: [0, 0, 0, 0]\n"
         << "  resolution: [32, 24]\n";
  }
  file.close();
  const CommandResult which =
      RunAperture(run + "--frontends gap --calib " + camchain + " --out " + temp.path() + "/c");
  EXPECT_EQ(which.exit_code, 2) << which.output;
  EXPECT_TRUE(OutputHas(which.output, "--camera")) << which.output;
  const CommandResult typo = RunAperture(run + "--frontends gap --calib " + camchain +
                                         " --camera cam3 --out " + temp.path() + "/d");
  EXPECT_EQ(typo.exit_code, 2) << typo.output;
  EXPECT_TRUE(OutputHas(typo.output, "has no camera 'cam3'; its cameras: cam0, cam1"))
      << typo.output;
  const CommandResult chosen = RunAperture(run + "--frontends gap --calib " + camchain +
                                           " --camera cam1 --out " + temp.path() + "/e");
  EXPECT_EQ(chosen.exit_code, 0) << chosen.output;
  // apriltag.sizes is keyed by tag id: another key is a --set mistake.
  const CommandResult sizes =
      RunAperture(run + "--frontends apriltag --calib " + (data / "calib.yaml").string() +
                  " --set apriltag.sizes.x=0.1 --out " + temp.path() + "/f");
  EXPECT_EQ(sizes.exit_code, 2) << sizes.output;
  EXPECT_TRUE(OutputHas(sizes.output, "'apriltag.sizes.x' is not a tag id")) << sizes.output;
}

TEST(ValuesCli, AnUnknownNameInAnOptionIsAUsageErrorListingTheKnownOnes) {
  TempFolder temp("values_names_in_options");
  const fs::path data = fs::path(temp.path()) / "data";
  ASSERT_EQ(
      RunAperture("render gap --frames 1" + kValuesTinyFront + "--out " + data.string()).exit_code,
      0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bench gapflyt --laws moments,momnets", "'momnets' is not one of: moments, pid"},
      {"bench ts2p --methods dis_fast,disfast", "'disfast' is not one of: "},
      {"bench control --only drag,dragg", "unknown section 'dragg'"},
      {"sim gap --mission gapp", "unknown mission 'gapp'"},
      {"sim gap --set mission=gapp", "unknown mission 'gapp'"},
      {"run --source " + data.string() + " --frontends image_quality,gapp",
       "unknown front end 'gapp'"},
      {"calibrate --images " + (data / "images").string() + " --pattern chess:9x6",
       "--pattern 'chess:9x6'"}};
  for (const auto& [command, expected] : cases) {
    const CommandResult result = RunAperture(command + " --out " + temp.path() + "/out");
    EXPECT_EQ(result.exit_code, 2) << command << ": " << result.output;
    EXPECT_TRUE(OutputHas(result.output, expected)) << command << ": " << result.output;
    fs::remove_all(fs::path(temp.path()) / "out");  // a failed run's summary.json
  }
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
