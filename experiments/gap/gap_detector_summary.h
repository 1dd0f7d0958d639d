#pragma once
// The figures of the detector section of `aperture bench gap` (gap_detector_sequence.h) against
// issue 22's targets, over the frames that show the whole pattern at a distance inside the
// sequences' range: the detection rate, and the medians of the rotation error, of |p_CG| error
// and of |p_GC| error (both in % of the distance), overall and by distance, camera speed, view
// angle and gap roll.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/gap/gap_detector_sequence.h"
#include "output/html_report.h"

namespace aperture::experiments {

// Issue 22, "gap detection under motion": the targets of the detector section.
struct GapDetectorTargets {
  double min_detection_rate = 0.95;
  double max_rotation_median_deg = 0.25;
  double max_T_GC_position_median_pct = 0.4;
  double max_T_CG_position_median_pct = 0.1;
};

// summary.json "detector": the figures, their targets and whether each is met. `distance_m`:
// the sequences' distance range (frames outside it are not scored).
nlohmann::json SummarizeGapDetectorSequences(const std::vector<GapDetectorSequenceRecord>& records,
                                             const Eigen::Vector2d& distance_m);

// One row per rendered frame (sequence draws and the frame's scores).
void WriteGapDetectorFramesCsv(const std::vector<GapDetectorSequenceRecord>& records,
                               const std::string& path);

// The report's "Detector on moving sequences" section: the outcome against the targets, the
// tables by distance, speed, view angle and roll, and the errors against the distance.
void AddGapDetectorReportSection(const nlohmann::json& detector_summary,
                                 const std::vector<GapDetectorSequenceRecord>& records,
                                 output::HtmlReport* report);

}  // namespace aperture::experiments
