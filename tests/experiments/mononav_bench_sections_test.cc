// The summary sections and flights.csv of `aperture bench mononav` from constructed flights
// (WriteMononavSections): Table II's replans per flight and per waypoint selection, the
// recoveries per configuration, and a run of no_edt alone.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/mononav/mononav_bench.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::experiments {
namespace {

struct MononavCounts {
  int replans = 0;
  int selections = 0;
  int frames_replanned = 0;
  int back_offs = 0;
  int look_asides = 0;
};

MononavFlight ConstructedFlight(const std::string& configuration, std::uint64_t seed, bool passed,
                                const MononavCounts& n) {
  MononavFlight f;
  f.configuration = configuration;
  f.seed = seed;
  f.evaluation.passed = passed;
  f.evaluation.outcome = passed ? "reached" : "failed";
  f.evaluation.figures = {{"reached_goal", passed},
                          {"collision", false},
                          {"replans", n.replans},
                          {"selections", n.selections},
                          {"frames_replanned", n.frames_replanned},
                          {"frames", n.selections},
                          {"back_offs", n.back_offs},
                          {"look_asides", n.look_asides},
                          {"perception_ms", {{"median", 9.0}, {"max", 20.0}, {"frames", 10}}},
                          {"planning_ms", {{"median", 4.0}, {"max", 8.0}, {"frames", 10}}}};
  f.outcome = "autopilot_done";
  return f;
}

// The CSV's rows as column name -> cell.
std::vector<std::vector<std::pair<std::string, std::string>>> ReadMononavCsv(
    const std::string& path) {
  std::ifstream in(path);
  std::string line, cell;
  std::vector<std::string> names;
  std::getline(in, line);
  for (std::stringstream h(line); std::getline(h, cell, ',');) names.push_back(cell);
  std::vector<std::vector<std::pair<std::string, std::string>>> rows;
  while (std::getline(in, line) && !line.empty()) {
    rows.emplace_back();
    std::stringstream r(line);
    for (const std::string& name : names) {
      std::getline(r, cell, ',');
      rows.back().emplace_back(name, cell);
    }
  }
  return rows;
}

std::string MononavCsvCell(const std::vector<std::pair<std::string, std::string>>& row,
                           const std::string& name) {
  for (const auto& [column, value] : row) {
    if (column == name) return value;
  }
  ADD_FAILURE() << "no column " << name;
  return "";
}

class MononavBenchSections : public testing::TempDirectoryTest {};

TEST_F(MononavBenchSections, ReplansPerSelectionAndRecoveriesPerConfiguration) {
  MononavBenchOptions options;
  options.trials = 2;
  options.flights_csv_path = (directory_ / "flights.csv").string();
  // Two layouts, each flown in edt, no_edt, random_waypoint.
  const std::vector<MononavFlight> flights = {
      ConstructedFlight("edt", 1, true, {30, 100, 20, 0, 0}),
      ConstructedFlight("no_edt", 1, false, {10, 400, 5, 3, 0}),
      ConstructedFlight("random_waypoint", 1, true, {500, 200, 150, 0, 2}),
      ConstructedFlight("edt", 2, true, {90, 200, 40, 1, 1}),
      ConstructedFlight("no_edt", 2, true, {20, 300, 10, 0, 0}),
      ConstructedFlight("random_waypoint", 2, true, {100, 100, 50, 0, 0})};
  nlohmann::json summary;
  output::HtmlReport report("test");
  WriteMononavSections(options, flights, &summary, &report);

  // Per flight: (30 + 90) / 2; per selection: 120 replans over 300 selections; 60 of the 300
  // selections rejected their first segment.
  const nlohmann::json& optimal = summary["table_ii"]["optimal"];
  EXPECT_DOUBLE_EQ(optimal["replans_mean"].get<double>(), 60.0);
  EXPECT_DOUBLE_EQ(optimal["replans_per_selection"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(optimal["selections_replanned_percent"].get<double>(), 20.0);
  const nlohmann::json& random = summary["table_ii"]["random"];
  EXPECT_DOUBLE_EQ(random["replans_per_selection"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(random["selections_replanned_percent"].get<double>(), 200.0 / 3.0);
  EXPECT_TRUE(summary["acceptance"]["optimal_fewer_replans_than_random"].get<bool>());

  EXPECT_DOUBLE_EQ(summary["table_iv"]["improvement_percent_points"].get<double>(), 50.0);
  const nlohmann::json& edt = summary["success"]["edt"];
  EXPECT_EQ(edt["success"], 2);
  EXPECT_EQ(edt["flights_with_recovery"], 1);
  EXPECT_EQ(edt["back_offs"].get<double>(), 1.0);
  EXPECT_EQ(edt["look_asides"].get<double>(), 1.0);
  EXPECT_EQ(summary["success"]["no_edt"]["back_offs"].get<double>(), 3.0);
  EXPECT_EQ(summary["success"]["random_waypoint"]["flights_with_recovery"], 1);

  const auto rows = ReadMononavCsv(options.flights_csv_path);
  ASSERT_EQ(rows.size(), flights.size());
  EXPECT_EQ(MononavCsvCell(rows[1], "configuration"), "no_edt");
  EXPECT_EQ(std::stod(MononavCsvCell(rows[1], "back_offs")), 3.0);
  EXPECT_EQ(std::stod(MononavCsvCell(rows[2], "look_asides")), 2.0);
  EXPECT_EQ(std::stod(MononavCsvCell(rows[2], "selections")), 200.0);
  EXPECT_EQ(std::stod(MononavCsvCell(rows[2], "frames_replanned")), 150.0);
}

// no_edt alone (to add Table IV's other row to edt runs flown before): its row and success
// only; no timing, improvement or acceptance check that needs edt.
TEST_F(MononavBenchSections, NoEdtAloneWritesItsOwnRowOnly) {
  MononavBenchOptions options;
  options.trials = 2;
  options.configurations = {"no_edt"};
  options.Validate();
  const std::vector<MononavFlight> flights = {
      ConstructedFlight("no_edt", 1, false, {10, 400, 5, 0, 2}),
      ConstructedFlight("no_edt", 2, true, {20, 300, 10, 0, 0})};
  nlohmann::json summary;
  output::HtmlReport report("test");
  WriteMononavSections(options, flights, &summary, &report);
  const nlohmann::json& without = summary["table_iv"]["without_edt"];
  EXPECT_EQ(without["flights"], 2);
  EXPECT_EQ(without["success"], 1);
  EXPECT_EQ(without["look_asides"].get<double>(), 2.0);
  EXPECT_FALSE(summary["table_iv"].contains("with_edt"));
  EXPECT_FALSE(summary["table_iv"].contains("improvement_percent_points"));
  EXPECT_FALSE(summary.contains("timing"));
  EXPECT_TRUE(summary["acceptance"].is_object());
  EXPECT_TRUE(summary["acceptance"].empty());
}

}  // namespace
}  // namespace aperture::experiments
