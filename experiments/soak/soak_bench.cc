#include "experiments/soak/soak_bench.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "experiments/missions/fly_mission.h"
#include "experiments/soak/soak_figures.h"
#include "experiments/soak/soak_sampler.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/interruption.h"
#include "output/process_resources.h"
#include "output/progress_bar.h"
#include "output/svg_plot.h"

namespace aperture::experiments {
namespace {

constexpr const char* kSoakScenario = "led";

std::vector<double> SoakRow(const SoakSample& s) {
  return {s.t_s,
          s.wall_s,
          s.cpu_s,
          s.rss_mib,
          static_cast<double>(s.frames),
          s.frame_wall_median_ms,
          s.frame_wall_max_ms,
          s.frame_cpu_median_ms,
          s.frame_cpu_max_ms};
}

// A record vector's length and the memory it holds (capacity x element size).
template <typename Record>
nlohmann::json BufferJson(const std::vector<Record>& records) {
  return {{"size", records.size()},
          {"capacity", records.capacity()},
          {"bytes", records.capacity() * sizeof(Record)}};
}

std::string SoakText(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

output::ReportOutcome SoakOutcome(const SoakFigures& f, double sim_time_s) {
  output::ReportOutcome outcome;
  outcome.verdict = f.rss_growth_ok ? "passed" : "failed";
  outcome.headline = SoakText("Resident memory grew %+.2f %% from t = %.0f s", f.rss_growth_percent,
                              f.rss_reference_t_s) +
                     SoakText(" to the end of %.0f s simulated (LED hover).", sim_time_s);
  outcome.figures.push_back({"RSS growth after the reference",
                             SoakText("%.1f -> %.1f MiB (%+.2f %%)", f.rss_reference_mib,
                                      f.rss_end_mib, f.rss_growth_percent),
                             SoakText("< %.0f %%", f.check.max_rss_growth_percent)});
  outcome.figures.push_back(
      {SoakText("per-frame CPU median, first / last %.0f s", f.check.timing_window_s),
       SoakText("%.2f / %.2f ms (%+.1f %%)", f.frame_cpu_median_first_ms,
                f.frame_cpu_median_last_ms, f.frame_cpu_drift_percent),
       "no drift"});
  outcome.figures.push_back(
      {SoakText("per-frame wall median, first / last %.0f s", f.check.timing_window_s),
       SoakText("%.2f / %.2f ms (%+.1f %%)", f.frame_wall_median_first_ms,
                f.frame_wall_median_last_ms, f.frame_wall_drift_percent),
       "(shared machine: CPU is the figure)"});
  return outcome;
}

void WriteSoakReport(const std::vector<SoakSample>& samples, const SoakFigures& figures,
                     double sim_time_s, output::OutputFolder& out) {
  output::HtmlReport report("aperture bench soak");
  report.AddOutcome(SoakOutcome(figures, sim_time_s));
  report.AddRunDescription(out.summary(), out.ElapsedSeconds());
  std::vector<double> t, rss, cpu_median, cpu_max, wall_median, wall_max;
  for (const SoakSample& s : samples) {
    t.push_back(s.t_s);
    rss.push_back(s.rss_mib);
    cpu_median.push_back(s.frame_cpu_median_ms);
    cpu_max.push_back(s.frame_cpu_max_ms);
    wall_median.push_back(s.frame_wall_median_ms);
    wall_max.push_back(s.frame_wall_max_ms);
  }
  report.AddSection("Memory");
  report.AddSvg(output::SvgPlot({"Resident memory (VmRSS)", "simulated t [s]", "RSS [MiB]"})
                    .AddLine("RSS", t, rss)
                    .Render());
  report.AddSection("Per-frame time");
  report.AddSvg(output::SvgPlot({"Per-frame time, median per interval", "simulated t [s]",
                                 "time per frame [ms]"})
                    .AddLine("thread CPU", t, cpu_median)
                    .AddLine("wall", t, wall_median)
                    .Render());
  report.AddSvg(output::SvgPlot({"Per-frame time, maximum per interval", "simulated t [s]",
                                 "time per frame [ms]"})
                    .AddLine("thread CPU", t, cpu_max)
                    .AddLine("wall", t, wall_max)
                    .Render());
  report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
  report.Write(out.Path("report.html"));
}

}  // namespace

void RunSoakBench(const SoakBenchOptions& options, output::OutputFolder& out) {
  if (!(options.interval_s > 0.0) || !(options.interval_s <= options.duration_s)) {
    throw std::invalid_argument(
        "the soak's sampling interval (--interval) must be positive and "
        "at most the duration (--duration)");
  }
  nlohmann::json& summary = out.summary();
  summary["command"] = "bench soak";
  summary["inputs"] = {{"scenario", kSoakScenario},
                       {"seed", options.seed},
                       {"duration_s", options.duration_s},
                       {"interval_s", options.interval_s},
                       {"record_window_s", kSoakRecordWindowS},
                       {"set", options.set_items}};

  output::CsvWriter csv(out.Path("soak.csv"),
                        {"t_s", "wall_s", "cpu_s", "rss_mib", "frames", "frame_wall_median_ms",
                         "frame_wall_max_ms", "frame_cpu_median_ms", "frame_cpu_max_ms"});
  SoakSampler sampler(options.interval_s);
  std::vector<SoakSample> samples;  // duration / interval of them: the plots' points
  const auto keep = [&](const SoakSample& sample) {
    csv.WriteRow(SoakRow(sample));
    samples.push_back(sample);
  };
  output::ProgressBar progress("simulated s", static_cast<std::size_t>(options.duration_s));
  double last_frame_t_s = 0.0;
  nlohmann::json buffers;

  MissionFlightSpec spec;
  spec.scenario = kSoakScenario;
  spec.set_items = options.set_items;
  spec.seed = options.seed;
  spec.duration_s = options.duration_s;
  spec.record_window_s = kSoakRecordWindowS;
  spec.on_frame = [&](int camera_index, double t_s) {
    if (camera_index != 0) return;  // the per-frame cost of the first camera's frame rate
    last_frame_t_s = t_s;
    if (const std::optional<SoakSample> sample = sampler.OnFrame(t_s)) keep(*sample);
    progress.Update(static_cast<std::size_t>(t_s));
  };
  spec.stop_requested = [] { return output::InterruptionRequested(); };
  spec.on_result = [&](const sim::SitlResult& result) {
    if (const std::optional<SoakSample> sample = sampler.Finish(last_frame_t_s)) keep(*sample);
    buffers = {{"sitl_trajectory", BufferJson(result.trajectory)},
               {"sitl_commands", BufferJson(result.commands)},
               {"sitl_imu", BufferJson(result.imu)},
               {"sitl_range", BufferJson(result.range)}};
  };
  const double cpu_start_s = output::ThreadCpuSeconds();
  const MissionFlightRun run = FlyMission(spec);
  const double cpu_s = output::ThreadCpuSeconds() - cpu_start_s;
  progress.Finish();
  csv.Close();

  buffers["led_hover_estimates"] = {
      {"size", run.evaluation.figures.at("estimate_error_m").at("samples")}};
  buffers["soak_samples"] = BufferJson(samples);
  summary["buffers"] = buffers;
  summary["mission"] = run.evaluation.figures;
  summary["mission"]["passed"] = run.evaluation.passed;
  summary["mission"]["outcome"] = run.evaluation.outcome;
  summary["mission"]["scored_over_last_s"] = kSoakRecordWindowS;
  summary["run"] = {
      {"sim_outcome", run.sim_outcome},
      {"sim_time_s", run.sim_time_s},
      {"wall_time_s", run.wall_time_s},
      {"cpu_time_s", cpu_s},
      {"real_time_factor", run.wall_time_s > 0.0 ? run.sim_time_s / run.wall_time_s : 0.0}};
  summary["outputs"] = {{"samples", "soak.csv"}, {"report", "report.html"}};
  const SoakFigures figures = ComputeSoakFigures(samples, SoakCheckParamsFor(run.sim_time_s));
  summary["soak"] = SoakFiguresJson(figures);
  summary["acceptance"] = SoakAcceptanceJson(figures);
  WriteSoakReport(samples, figures, run.sim_time_s, out);
  std::printf(
      "aperture bench soak: RSS %.1f MiB at t = %.0f s, %.1f MiB at %.0f s (%+.2f %%); "
      "per-frame CPU median %.2f -> %.2f ms\n",
      figures.rss_reference_mib, figures.rss_reference_t_s, figures.rss_end_mib,
      figures.rss_end_t_s, figures.rss_growth_percent, figures.frame_cpu_median_first_ms,
      figures.frame_cpu_median_last_ms);
}

}  // namespace aperture::experiments
