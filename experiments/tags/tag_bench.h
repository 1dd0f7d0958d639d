#pragma once
// `aperture bench tags` (issue 15): the AprilTag front end on frames ray-traced by the simulator
// against their ground truth. Sections, each under its own summary key:
//   detection  per detector (every registered one) and family (36h11, 16h5, 25h9, 41h12):
//              single 0.16 m tags at 0.5-6 m, view angles 0-70 deg, a third with motion blur
//              (10 ms exposure at 1 m/s); detection rate, translation / rotation error (the
//              candidate nearer the truth, so flips do not count here), ms per frame
//   mapping    a lawn-mower pass (4 lanes, 2.5 m height) over the `tags` scenario (4 x 6 m,
//              paper D) with the onboard estimate per image: gravity 1 deg off per axis and
//              odometry drifting as the map's random walk assumes: flip rate of the chosen pose
//              with and without TagFlipResolver; the TagMap from the resolved observations: tag
//              position RMS before (chained initialisation) and after optimization, in the
//              origin tag's frame, with and without the odometry edges; tags whose mapped
//              rotation is > 10 deg off (flipped) for resolved and unresolved inputs
//   missions   paper D's ground-robot mission planner on random scenes: planning time per number
//              of movable obstacles, solve rate, Alg. 2 against exhaustive search
//              (missions_bench_section.h)
//   acceptance booleans: map RMS <= 2 cm, no flipped tag in the map; missions solved >= 99 %,
//              Alg. 2 equal to the exhaustive search
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "output/html_report.h"
#include "perception/tags/tag_detector_registry.h"

namespace aperture::experiments {

struct TagBenchOptions {
  std::uint64_t seed = 1;
  bool quick = false;  // fewer frames, same code paths (ctest smoke test)
  perception::TagDetectorRegistry detectors = perception::TagDetectorRegistry::WithBuiltins();
  std::string frames_csv_path;  // per detection frame of the detection section; empty = none
  // Per tag observation of the mapping pass (its pose and corners against the truth); empty = none
  std::string observations_csv_path;
  // The sections to run, in TagBenchSectionKeys() order whatever the order here; empty = all.
  std::vector<std::string> sections;
};

// The section keys in the order they run: "detection", "mapping", "missions".
std::vector<std::string> TagBenchSectionKeys();
// The keys of options.sections in run order (all when empty); std::invalid_argument naming an
// unknown one.
std::vector<std::string> SelectedTagBenchSections(const TagBenchOptions& options);

// Runs section `key` on its own (each draws from options.seed alone, so it gives the same
// figures whatever else runs): its record {"section", "summary" (its keys; mapping also writes
// "acceptance"), "report" (its blocks), "frames" (detection: its frames.csv rows), "wall_time_s"}
// (experiments/bench/section_record.h). std::invalid_argument for an unknown key.
nlohmann::json RunTagBenchSection(const std::string& key, const TagBenchOptions& options);

// The bench's outputs from the records of the sections run, in order: figures into *summary,
// blocks into *report, frames.csv to options.frames_csv_path and observations.csv to
// options.observations_csv_path when set.
void WriteTagBenchOutputs(const TagBenchOptions& options,
                          const std::vector<nlohmann::json>& section_records,
                          nlohmann::json* summary, output::HtmlReport* report);

}  // namespace aperture::experiments
