// `aperture bench tags --quick` end to end: every section of issues 15 and 16's bench is written
// and the quick mapping pass meets the map acceptance against the scenario's ground truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchTagsCommand, QuickRunMapsTheFieldWithinTwoCentimetres) {
  TempFolder out("bench_tags");
  const CommandResult run = RunAperture("bench tags --quick --seed 2 --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  for (const char* detector : {"apriltag", "visp"}) {
    for (const char* family : {"tag36h11", "tag16h5", "tag25h9", "tagStandard41h12"}) {
      const nlohmann::json& cell = summary["detection"][detector][family];
      ASSERT_TRUE(cell.is_object()) << detector << " " << family;
      // Debian's ViSP is built without the tagStandard41h12 family.
      const bool visp_41h12 =
          std::string(detector) == "visp" && std::string(family) == "tagStandard41h12";
      ASSERT_EQ(cell["supported"], !visp_41h12) << detector << " " << family;
      if (visp_41h12) continue;
      // Close, moderately tilted tags are always found (the quick set has 6 views per family).
      EXPECT_GT(cell["detection_rate"].get<double>(), 0.3) << detector << " " << family;
      EXPECT_LT(cell["median_translation_error_m"].get<double>(), 0.05)
          << detector << " " << family;
    }
  }
  const nlohmann::json& mapping = summary["mapping"];
  // The map against the scenario's tag poses (the truth), in the origin tag's frame.
  EXPECT_LE(mapping["map_rms_after_m"].get<double>(), 0.02);
  EXPECT_EQ(mapping["map_flipped_tags"], 0);
  EXPECT_LT(mapping["map_rms_after_m"].get<double>(), mapping["map_rms_before_m"].get<double>());
  EXPECT_EQ(mapping["tags_mapped"], mapping["tags_in_scene"]);
  // The rendered corners against the projected truth: sub-pixel.
  EXPECT_LT(mapping["corner_error_median_px"].get<double>(), 0.3);
  EXPECT_LE(mapping["flip_rate_resolved"].get<double>(),
            mapping["flip_rate_lowest_error"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/frames.csv"));
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/report.html"));
  EXPECT_EQ(summary["acceptance"]["missions_equal_exhaustive_search"], true);
}

// --section missions runs the ground-robot planner's section alone (no rendering): its figures
// and acceptance, nothing of the other sections. An unknown section is a usage error.
TEST(BenchTagsCommand, MissionsSectionAlone) {
  TempFolder out("bench_tags_missions");
  const CommandResult run =
      RunAperture("bench tags --quick --section missions --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_FALSE(summary.contains("detection"));
  EXPECT_FALSE(summary.contains("mapping"));
  const nlohmann::json& missions = summary["missions"];
  EXPECT_EQ(missions["scenes"], 50);  // quick: 10 per number of movable obstacles 2-10
  EXPECT_EQ(missions["equal_to_exhaustive"], missions["compared_scenes"]);
  EXPECT_EQ(summary["acceptance"]["missions_solved_at_least_99pct"], true);
  EXPECT_EQ(missions["timing"].size(), 5u);
  const CommandResult unknown =
      RunAperture("bench tags --quick --section planning --out " + out.path() + "/unknown");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
}

}  // namespace
}  // namespace aperture::apps::testing
