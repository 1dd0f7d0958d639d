#pragma once
// What `aperture run` keeps of a run to report it: the metric rows, a few key frames with their
// overlays, and the functions that turn them into summary.json entries and report.html.
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "output/output_folder.h"
#include "perception/graph/timing_stats.h"
#include "perception/sensor_data.h"

namespace aperture::apps {

class RunRecord {
 public:
  static constexpr std::size_t kKeyFrames = 4;

  // `row` = {t_s, index, metrics...} as written to frames.csv. `expected_frames` (0 = unknown)
  // spreads the kept key frames over the run; the last frame is always kept.
  void Add(const perception::Frame& frame, const std::vector<double>& row, const cv::Mat& overlay,
           std::size_t expected_frames);
  std::size_t frame_count() const { return rows_.size(); }
  const std::vector<std::vector<double>>& rows() const { return rows_; }

  struct KeyFrame {
    int index;
    double t_s;
    cv::Mat overlay;
  };
  // Key frames in time order (the last frame included).
  std::vector<KeyFrame> KeyFrames() const;

  // {"<metric>": {"mean", "min", "max"}} over frames, NaN-aware (count of finite values too).
  nlohmann::json MetricStatistics(const std::vector<std::string>& metric_names) const;

 private:
  std::vector<std::vector<double>> rows_;
  std::vector<KeyFrame> key_frames_;
  KeyFrame last_;
};

// summary.json "timing": {"nodes": {"<node>": {count, median_s, p95_s, max_s}}, "frame": {...}}.
nlohmann::json TimingJson(const std::vector<perception::NodeTiming>& nodes,
                          const perception::TimingStats& frame);

// report.html: the outcome (frames, poses per stream, time per frame), what was run, one plot per
// scalar metric over time, the mean of each vector metric (keys "<stem>_<NN>") over its
// components, the timing table, the key frames and, folded, every figure of summary.json.
void WriteRunReport(output::OutputFolder& out, const RunRecord& record,
                    const std::vector<std::string>& metric_names);

}  // namespace aperture::apps
