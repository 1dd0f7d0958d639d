// `aperture bench mononav --quick` end to end: one forest flight around a trunk on the line to a
// goal 4 m away, scored on ground truth; the summary has the issue's sections and the flight's
// figures agree with the course's geometry.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchMononavCommand, QuickFlightPassesTheTrunkAndWritesTheIssueSections) {
  TempFolder out("bench_mononav");
  const CommandResult run = RunAperture("bench mononav --quick --duration 15 --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  ASSERT_EQ(summary["status"], "ok") << summary.dump(2);
  const nlohmann::json& with_edt = summary["table_iv"]["with_edt"];
  EXPECT_EQ(with_edt["flights"], 1);
  EXPECT_EQ(with_edt["success"], 1) << summary.dump(2);
  EXPECT_TRUE(summary["table_ii"]["optimal"]["replans_mean"].is_number());
  for (const char* module : {"perception", "planning"}) {
    EXPECT_GT(summary["timing"][module]["median_ms"].get<double>(), 0.0) << module;
    EXPECT_GT(summary["timing"][module]["frames"].get<int>(), 0) << module;
  }
  EXPECT_TRUE(summary["acceptance"].contains("perception_at_most_50_ms"));

  // flights.csv: one row; its ground-truth path cannot be shorter than the straight line from the
  // start (0, 0) to the 1 m goal radius around (4, 0): 3 m, and the detour round the trunk on that
  // line makes it longer.
  std::ifstream csv(out.path() + "/flights.csv");
  std::string header, row, extra;
  ASSERT_TRUE(std::getline(csv, header));
  ASSERT_TRUE(std::getline(csv, row));
  EXPECT_FALSE(std::getline(csv, extra) && !extra.empty());
  std::vector<std::string> names, cells;
  for (std::stringstream h(header); std::getline(h, extra, ',');) names.push_back(extra);
  for (std::stringstream r(row); std::getline(r, extra, ',');) cells.push_back(extra);
  ASSERT_EQ(names.size(), cells.size());
  const auto cell = [&](const std::string& name) {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return std::stod(cells[i]);
    }
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  EXPECT_EQ(cell("success"), 1.0);
  EXPECT_GT(cell("path_length_m"), 3.0);
  // Rotor tips reach 0.24 m from the body centre: the trunk was passed without touching.
  EXPECT_GT(cell("min_clearance_m"), 0.24);
  // The trunk 3 m ahead is passed without a stall: no recovery, and every selection counted.
  EXPECT_EQ(cell("back_offs"), 0.0);
  EXPECT_EQ(cell("look_asides"), 0.0);
  EXPECT_GT(cell("selections"), 0.0);
  EXPECT_LE(cell("selections"), cell("frames"));
  EXPECT_LE(cell("frames_replanned"), cell("selections"));
  EXPECT_EQ(summary["success"]["edt"]["flights_with_recovery"], 0);
}

// --configurations chooses what is flown; a name it does not know is refused before any flight,
// naming the value.
TEST(BenchMononavCommand, RefusesUnknownConfigurations) {
  TempFolder out("bench_mononav_configurations");
  const CommandResult unknown =
      RunAperture("bench mononav --configurations edt,no_edtt --out " + out.path());
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("unknown configuration 'no_edtt'"), std::string::npos)
      << unknown.output;
}

}  // namespace
}  // namespace aperture::apps::testing
