#include "experiments/gap/gap_detector_summary.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "experiments/bench/sample_statistics.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"

namespace aperture::experiments {
namespace {

// A scored frame with the draws of its sequence.
struct ScoredFrame {
  const GapDetectorSequenceConfig* sequence;
  const GapDetectorFrameRecord* frame;
  bool detected() const { return frame->status == perception::GapDetectionStatus::kDetected; }
};

struct Bin {
  std::string name;
  double lo, hi;  // [lo, hi)
};

nlohmann::json Figures(const std::vector<ScoredFrame>& frames) {
  std::vector<double> rotation, T_CG_pct, T_GC_pct;
  for (const ScoredFrame& s : frames) {
    if (!s.detected()) continue;
    const double distance = s.frame->distance_m;
    rotation.push_back(s.frame->error.rotation_deg);
    T_CG_pct.push_back(100.0 * s.frame->error.T_CG_position_m / distance);
    T_GC_pct.push_back(100.0 * s.frame->error.T_GC_position_m / distance);
  }
  const double n = static_cast<double>(frames.size());
  return {{"frames_in_view", frames.size()},
          {"detected", rotation.size()},
          {"detection_rate", FiniteOrNull(static_cast<double>(rotation.size()) / n)},
          {"rotation_error_median_deg", FiniteOrNull(UpperMedian(rotation))},
          {"T_CG_position_error_median_pct", FiniteOrNull(UpperMedian(T_CG_pct))},
          {"T_GC_position_error_median_pct", FiniteOrNull(UpperMedian(T_GC_pct))}};
}

nlohmann::json ByBins(const std::vector<ScoredFrame>& frames, const std::vector<Bin>& bins,
                      const std::function<double(const ScoredFrame&)>& value) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Bin& bin : bins) {
    std::vector<ScoredFrame> in_bin;
    for (const ScoredFrame& s : frames) {
      const double v = value(s);
      if (v >= bin.lo && v < bin.hi) in_bin.push_back(s);
    }
    nlohmann::json row = Figures(in_bin);
    row["bin"] = bin.name;
    rows.push_back(row);
  }
  return rows;
}

bool AtMost(const nlohmann::json& figure, double target) {
  return figure.is_number() && figure.get<double>() <= target;
}

}  // namespace

nlohmann::json SummarizeGapDetectorSequences(const std::vector<GapDetectorSequenceRecord>& records,
                                             const Eigen::Vector2d& distance_m) {
  std::vector<ScoredFrame> scored;
  int frames = 0, detections_not_scored = 0, failed_sequences = 0;
  std::map<std::string, int> misses;
  for (const GapDetectorSequenceRecord& r : records) {
    if (!r.error.empty()) ++failed_sequences;
    for (const GapDetectorFrameRecord& f : r.frames) {
      ++frames;
      const ScoredFrame s{&r.config, &f};
      const bool in_range = f.distance_m >= distance_m.x() && f.distance_m <= distance_m.y();
      if (f.in_view && in_range) {
        scored.push_back(s);
        if (!s.detected()) ++misses[perception::GapDetectionStatusName(f.status)];
      } else if (s.detected()) {
        ++detections_not_scored;
      }
    }
  }
  nlohmann::json summary = {
      {"definition",
       "frames that show the whole pattern (every outer corner in the image on the gap panel) "
       "at a distance inside the sequences' range; errors of detected frames against the "
       "renderer's ground truth at mid-exposure, the pattern's symmetry resolved by the truth; "
       "position errors in % of the camera-to-gap distance, medians over frames"},
      {"sequences", records.size()},
      {"failed_sequences", failed_sequences},
      {"frames", frames},
      {"detections_not_scored", detections_not_scored},
      {"misses_by_status", misses}};
  const nlohmann::json overall = Figures(scored);
  for (const auto& [key, figure] : overall.items()) summary[key] = figure;

  const GapDetectorTargets targets;
  const bool rate_met = overall["detection_rate"].is_number() &&
                        overall["detection_rate"].get<double>() >= targets.min_detection_rate;
  const bool rotation_met =
      AtMost(overall["rotation_error_median_deg"], targets.max_rotation_median_deg);
  const bool T_GC_met =
      AtMost(overall["T_GC_position_error_median_pct"], targets.max_T_GC_position_median_pct);
  const bool T_CG_met =
      AtMost(overall["T_CG_position_error_median_pct"], targets.max_T_CG_position_median_pct);
  summary["targets"] = {
      {"min_detection_rate", targets.min_detection_rate},
      {"max_rotation_error_median_deg", targets.max_rotation_median_deg},
      {"max_T_GC_position_error_median_pct", targets.max_T_GC_position_median_pct},
      {"max_T_CG_position_error_median_pct", targets.max_T_CG_position_median_pct},
      {"detection_rate_met", rate_met},
      {"rotation_met", rotation_met},
      {"T_GC_position_met", T_GC_met},
      {"T_CG_position_met", T_CG_met},
      {"all_met", rate_met && rotation_met && T_GC_met && T_CG_met}};

  summary["by_distance"] = ByBins(scored, {{"1-2 m", 0.0, 2.0}, {"2-4 m", 2.0, 4.0},
                                           {"4-6 m", 4.0, 1e9}},
                                  [](const ScoredFrame& s) { return s.frame->distance_m; });
  summary["by_speed"] = ByBins(scored, {{"0-1 m/s", 0.0, 1.0}, {"1-2 m/s", 1.0, 2.0},
                                        {"2-3 m/s", 2.0, 1e9}},
                               [](const ScoredFrame& s) { return s.sequence->speed_mps; });
  summary["by_view_angle"] =
      ByBins(scored, {{"0-20 deg", 0.0, 20.0}, {"20-40 deg", 20.0, 40.0}, {"40+ deg", 40.0, 1e9}},
             [](const ScoredFrame& s) { return s.frame->view_angle_deg; });
  summary["by_gap_roll"] =
      ByBins(scored, {{"0-30 deg", 0.0, 30.0}, {"30-45 deg", 30.0, 45.0}, {"45+ deg", 45.0, 1e9}},
             [](const ScoredFrame& s) { return s.sequence->roll_deg; });
  return summary;
}

void WriteGapDetectorFramesCsv(const std::vector<GapDetectorSequenceRecord>& records,
                               const std::string& path) {
  output::CsvWriter csv(path, {"sequence", "roll_deg", "pitch_deg", "speed_mps", "exposure_s",
                               "frame", "t_s", "distance_m", "view_angle_deg", "in_view",
                               "status", "from_roi", "T_CG_position_error_m",
                               "T_GC_position_error_m", "rotation_error_deg"});
  for (const GapDetectorSequenceRecord& r : records) {
    const GapDetectorSequenceConfig& c = r.config;
    for (const GapDetectorFrameRecord& f : r.frames) {
      std::vector<output::CsvCell> row;
      for (double v : {static_cast<double>(c.index), c.roll_deg, c.pitch_deg, c.speed_mps,
                       c.exposure_s, static_cast<double>(f.frame), f.t_s, f.distance_m,
                       f.view_angle_deg, f.in_view ? 1.0 : 0.0}) {
        row.emplace_back(v);
      }
      row.emplace_back(perception::GapDetectionStatusName(f.status));
      for (double v : {f.from_roi ? 1.0 : 0.0, f.error.T_CG_position_m, f.error.T_GC_position_m,
                       f.error.rotation_deg}) {
        row.emplace_back(v);
      }
      csv.WriteCells(row);
    }
  }
  csv.Close();
}

void AddGapDetectorReportSection(const nlohmann::json& s,
                                 const std::vector<GapDetectorSequenceRecord>& records,
                                 output::HtmlReport* report) {
  report->AddSection("Detector on moving sequences (issue 22)");
  const auto figure = [&](const char* key, double scale) {
    return s[key].is_number() ? s[key].get<double>() * scale : std::nan("");
  };
  char text[512];
  std::snprintf(text, sizeof(text),
                "Targets %s. %d sequences, %d frames with the whole pattern in view: detected in "
                "%.1f %% (target >= 95 %%); rotation median %.3f deg (<= 0.25); camera in the gap "
                "frame (T_GC) median %.3f %% of the distance (<= 0.4); gap in the camera (T_CG) "
                "median %.3f %% (<= 0.1).",
                s["targets"]["all_met"].get<bool>() ? "met" : "not met",
                s["sequences"].get<int>(), s["frames_in_view"].get<int>(),
                figure("detection_rate", 100.0), figure("rotation_error_median_deg", 1.0),
                figure("T_GC_position_error_median_pct", 1.0),
                figure("T_CG_position_error_median_pct", 1.0));
  report->AddParagraph(text);
  report->AddParagraph(s["definition"].get<std::string>());
  report->AddTable(s["by_distance"], "By distance to the gap");
  report->AddTable(s["by_speed"], "By camera speed");
  report->AddTable(s["by_view_angle"], "By view angle (gap normal vs line of sight)");
  report->AddTable(s["by_gap_roll"], "By gap roll");
  if (!s["misses_by_status"].empty()) report->AddTable(s["misses_by_status"], "Misses by status");

  std::vector<double> distance, rotation, T_GC_pct, missed_distance, missed_angle, hit_angle;
  for (const GapDetectorSequenceRecord& r : records) {
    for (const GapDetectorFrameRecord& f : r.frames) {
      if (!f.in_view) continue;
      if (f.status == perception::GapDetectionStatus::kDetected) {
        distance.push_back(f.distance_m);
        rotation.push_back(f.error.rotation_deg);
        T_GC_pct.push_back(100.0 * f.error.T_GC_position_m / f.distance_m);
        hit_angle.push_back(f.view_angle_deg);
      } else {
        missed_distance.push_back(f.distance_m);
        missed_angle.push_back(f.view_angle_deg);
      }
    }
  }
  report->AddSvg(output::SvgPlot({"Rotation error vs distance", "distance [m]", "error [deg]"})
                     .AddScatter("detected frames", distance, rotation)
                     .Render());
  report->AddSvg(
      output::SvgPlot({"Camera position in the gap frame (T_GC)", "distance [m]",
                       "error [% of distance]"})
          .AddScatter("detected frames", distance, T_GC_pct)
          .Render());
  report->AddSvg(output::SvgPlot({"Frames with the pattern in view", "distance [m]",
                                  "view angle [deg]"})
                     .AddScatter("detected", distance, hit_angle)
                     .AddScatter("missed", missed_distance, missed_angle)
                     .Render());
}

}  // namespace aperture::experiments
