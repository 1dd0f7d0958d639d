#include "apps/run_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <regex>

#include "output/html_report.h"
#include "output/svg_plot.h"

namespace aperture::apps {
namespace {

nlohmann::json StatsJson(const perception::TimingStats& stats) {
  return {{"count", stats.count},
          {"median_s", stats.median_s},
          {"p95_s", stats.p95_s},
          {"max_s", stats.max_s}};
}

// Metric columns start after t_s and index in each row.
constexpr std::size_t kFirstMetricColumn = 2;

}  // namespace

void RunRecord::Add(const perception::Frame& frame, const std::vector<double>& row,
                    const cv::Mat& overlay, std::size_t expected_frames) {
  const std::size_t position = rows_.size();
  rows_.push_back(row);
  // Evenly spaced key frames when the length is known, else the first ones.
  const std::size_t spacing =
      expected_frames > 0 ? std::max<std::size_t>(1, expected_frames / kKeyFrames) : 1;
  if (key_frames_.size() < kKeyFrames - 1 && position % spacing == 0) {
    key_frames_.push_back({frame.index, frame.t_s, overlay.clone()});
  }
  last_ = {frame.index, frame.t_s, overlay};  // the overlay is a fresh image per frame
}

std::vector<RunRecord::KeyFrame> RunRecord::KeyFrames() const {
  std::vector<KeyFrame> frames = key_frames_;
  if (!rows_.empty() && (frames.empty() || frames.back().index != last_.index)) {
    frames.push_back(last_);
  }
  return frames;
}

nlohmann::json RunRecord::MetricStatistics(const std::vector<std::string>& metric_names) const {
  nlohmann::json statistics = nlohmann::json::object();
  for (std::size_t m = 0; m < metric_names.size(); ++m) {
    double sum = 0.0, min = std::numeric_limits<double>::infinity(), max = -min;
    std::size_t count = 0;
    for (const auto& row : rows_) {
      const double value = row[kFirstMetricColumn + m];
      if (!std::isfinite(value)) continue;
      sum += value;
      min = std::min(min, value);
      max = std::max(max, value);
      ++count;
    }
    nlohmann::json entry = {{"finite_frames", count}};
    if (count > 0) {
      entry["mean"] = sum / count;
      entry["min"] = min;
      entry["max"] = max;
    }
    statistics[metric_names[m]] = entry;
  }
  return statistics;
}

nlohmann::json TimingJson(const std::vector<perception::NodeTiming>& nodes,
                          const perception::TimingStats& frame) {
  nlohmann::json per_node = nlohmann::json::object();
  for (const auto& node : nodes) per_node[node.node] = StatsJson(node.stats);
  return {{"nodes", per_node}, {"frame", StatsJson(frame)}};
}

namespace {

// `run` has no pass criterion: the outcome says what the front ends saw and how fast.
output::ReportOutcome RunOutcome(const nlohmann::json& summary) {
  const std::size_t frames = summary["frames"].get<std::size_t>();
  output::ReportOutcome outcome;
  outcome.verdict = "done";
  outcome.headline = std::to_string(frames) + " frames of " +
                     summary["inputs"]["source_description"].get<std::string>() + " through " +
                     summary["inputs"]["front_ends"].dump() + ", " +
                     std::to_string(summary["skipped_frames"].get<std::size_t>()) + " skipped.";
  for (const auto& [stream, pose] : summary["poses"].items()) {
    outcome.figures.push_back({stream + " poses",
                               std::to_string(pose["estimates"].get<std::size_t>()) + " of " +
                                   std::to_string(frames) + " frames",
                               ""});
  }
  const nlohmann::json& frame = summary["timing"]["frame"];
  char median_ms[32];
  std::snprintf(median_ms, sizeof(median_ms), "%.2f ms", frame["median_s"].get<double>() * 1e3);
  outcome.figures.push_back({"front ends per frame (median)", median_ms, ""});
  return outcome;
}

}  // namespace

void WriteRunReport(output::OutputFolder& out, const RunRecord& record,
                    const std::vector<std::string>& metric_names) {
  const nlohmann::json& summary = out.summary();
  output::HtmlReport report("aperture run: " + summary["inputs"]["source"].get<std::string>());
  report.AddOutcome(RunOutcome(summary));
  report.AddRunDescription(summary, out.ElapsedSeconds());
  if (!summary["skipped"].empty()) report.AddTable(summary["skipped"], "Skipped frames");

  std::vector<double> t_s;
  for (const auto& row : record.rows()) t_s.push_back(row[0]);
  // Vector metrics ("stem_NN") are summarized by their mean over frames per component.
  const std::regex component_pattern("(.*)_([0-9]+)$");
  std::map<std::string, std::vector<std::size_t>> vector_metrics;
  report.AddSection("Metrics over time");
  for (std::size_t m = 0; m < metric_names.size(); ++m) {
    std::smatch match;
    if (std::regex_match(metric_names[m], match, component_pattern)) {
      vector_metrics[match[1].str()].push_back(m);
      continue;
    }
    std::vector<double> values;
    for (const auto& row : record.rows()) values.push_back(row[kFirstMetricColumn + m]);
    report.AddSvg(output::SvgPlot({metric_names[m], "t [s]", metric_names[m]})
                      .AddLine(metric_names[m], t_s, values)
                      .Render());
  }
  for (const auto& [stem, columns] : vector_metrics) {
    std::vector<double> component, mean;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      double sum = 0.0;
      for (const auto& row : record.rows()) sum += row[kFirstMetricColumn + columns[c]];
      component.push_back(double(c));
      mean.push_back(sum / record.frame_count());
    }
    report.AddSvg(output::SvgPlot({stem + " (mean over frames)", "component", "mean"})
                      .AddLine(stem, component, mean)
                      .Render());
  }

  report.AddSection("Timing per node");
  nlohmann::json timing_rows = nlohmann::json::array();
  for (const auto& [node, stats] : summary["timing"]["nodes"].items()) {
    timing_rows.push_back({{"node", node},
                           {"frames", stats["count"]},
                           {"median [ms]", stats["median_s"].get<double>() * 1e3},
                           {"p95 [ms]", stats["p95_s"].get<double>() * 1e3},
                           {"max [ms]", stats["max_s"].get<double>() * 1e3}});
  }
  report.AddTable(timing_rows);

  report.AddSection("Key frames");
  for (const auto& key_frame : record.KeyFrames()) {
    report.AddImage(key_frame.overlay, "frame " + std::to_string(key_frame.index) + " at t = " +
                                           std::to_string(key_frame.t_s) + " s");
  }
  report.AddCollapsedTable(summary, "Every figure of summary.json");
  report.Write(out.Path("report.html"));
}

}  // namespace aperture::apps
