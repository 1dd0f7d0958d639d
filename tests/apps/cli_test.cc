// The command line contract: --help everywhere, exit code 2 for unknown flags and bad values,
// `bench` needs the name of a benchmark.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(Cli, VersionPrintsTheProjectVersion) {
  const CommandResult result = RunAperture("version");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("aperture " APERTURE_VERSION_FOR_TEST), std::string::npos)
      << result.output;
}

TEST(Cli, HelpListsEverySubcommand) {
  const CommandResult result = RunAperture("--help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* name : {"run", "sim", "render", "bench", "calibrate", "train", "version"}) {
    EXPECT_NE(result.output.find(name), std::string::npos) << name;
  }
}

TEST(Cli, UnknownFlagExitsWithTwoAndSaysWhy) {
  const CommandResult result = RunAperture("version --no-such-flag");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("--no-such-flag"), std::string::npos) << result.output;
}

TEST(Cli, MissingSubcommandExitsWithTwo) {
  EXPECT_EQ(RunAperture("").exit_code, 2);
  EXPECT_EQ(RunAperture("fly").exit_code, 2);
}

TEST(Cli, BenchWithoutABenchmarkNameExitsWithTwo) { EXPECT_EQ(RunAperture("bench").exit_code, 2); }

TEST(Cli, RenderNamesTheBuiltinScenariosForAnUnknownOne) {
  TempFolder temp("render-unknown");
  const CommandResult result = RunAperture("render nope --out " + temp.path() + "/out");
  EXPECT_EQ(result.exit_code, 2);  // a usage mistake
  EXPECT_NE(result.output.find("unknown scenario 'nope'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("gapflyt"), std::string::npos) << result.output;
}

TEST(Cli, SimAndRenderWithoutAScenarioListTheBuiltinOnes) {
  TempFolder temp("no-scenario");
  for (const std::string command : {"sim", "render"}) {
    const CommandResult result = RunAperture(command + " --out " + temp.path() + "/out");
    EXPECT_EQ(result.exit_code, 2) << command;  // a usage mistake
    EXPECT_NE(result.output.find("scenario NAME is required"), std::string::npos) << result.output;
    for (const char* name : {"gap", "gapflyt", "led", "tags", "forest"})
      EXPECT_NE(result.output.find(name), std::string::npos) << command << ": " << result.output;
  }
  EXPECT_NE(RunAperture("sim").output.find("tracking, recovery"), std::string::npos);
}

TEST(Cli, AFileGivenAsOutIsAUsageMistakeAndIsKept) {
  TempFolder temp("out-is-a-file");
  const std::string file = temp.path() + "/notes.txt";
  std::ofstream(file) << "mine";
  const CommandResult result = RunAperture("sim led --duration 0.1 --out " + file);
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("is a file"), std::string::npos) << result.output;
  std::ifstream kept(file);
  std::string text;
  kept >> text;
  EXPECT_EQ(text, "mine");
}

}  // namespace
}  // namespace aperture::apps::testing
