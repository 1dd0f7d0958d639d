#include "experiments/soak/soak_figures.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "experiments/bench/sample_statistics.h"

namespace aperture::experiments {
namespace {

double DriftPercent(double first, double last) { return 100.0 * (last - first) / first; }

}  // namespace

SoakCheckParams SoakCheckParamsFor(double duration_s) {
  SoakCheckParams check;
  check.rss_reference_s = std::min(check.rss_reference_s, 0.5 * duration_s);
  check.timing_window_s = std::min(check.timing_window_s, 0.5 * duration_s);
  return check;
}

SoakFigures ComputeSoakFigures(const std::vector<SoakSample>& samples,
                               const SoakCheckParams& check) {
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (!(samples[i].t_s > samples[i - 1].t_s)) {
      throw std::invalid_argument("soak samples: simulated times must increase (sample " +
                                  std::to_string(i) + ")");
    }
  }
  const auto reference = std::find_if(samples.begin(), samples.end(), [&](const SoakSample& s) {
    return s.t_s >= check.rss_reference_s - kSoakTimeTolS;
  });
  if (reference == samples.end()) {
    throw std::invalid_argument("soak samples: none at or after the memory reference t = " +
                                std::to_string(check.rss_reference_s) +
                                " s; fly longer than that (--duration)");
  }
  SoakFigures figures;
  figures.check = check;
  figures.rss_reference_t_s = reference->t_s;
  figures.rss_reference_mib = reference->rss_mib;
  figures.rss_end_t_s = samples.back().t_s;
  figures.rss_end_mib = samples.back().rss_mib;
  for (auto s = reference; s != samples.end(); ++s) {
    figures.rss_max_mib = std::max(figures.rss_max_mib, s->rss_mib);
  }
  figures.rss_growth_percent = DriftPercent(figures.rss_reference_mib, figures.rss_end_mib);
  figures.rss_growth_ok = figures.rss_growth_percent < check.max_rss_growth_percent;

  std::vector<double> cpu_first, cpu_last, wall_first, wall_last;
  const double last_from_s = figures.rss_end_t_s - check.timing_window_s;
  for (const SoakSample& s : samples) {
    if (s.frames == 0) continue;
    if (s.t_s <= check.timing_window_s + kSoakTimeTolS) {
      cpu_first.push_back(s.frame_cpu_median_ms);
      wall_first.push_back(s.frame_wall_median_ms);
    }
    if (s.t_s > last_from_s + kSoakTimeTolS) {
      cpu_last.push_back(s.frame_cpu_median_ms);
      wall_last.push_back(s.frame_wall_median_ms);
    }
  }
  figures.frame_cpu_median_first_ms = UpperMedian(cpu_first);
  figures.frame_cpu_median_last_ms = UpperMedian(cpu_last);
  figures.frame_cpu_drift_percent =
      DriftPercent(figures.frame_cpu_median_first_ms, figures.frame_cpu_median_last_ms);
  figures.frame_wall_median_first_ms = UpperMedian(wall_first);
  figures.frame_wall_median_last_ms = UpperMedian(wall_last);
  figures.frame_wall_drift_percent =
      DriftPercent(figures.frame_wall_median_first_ms, figures.frame_wall_median_last_ms);
  return figures;
}

nlohmann::json SoakFiguresJson(const SoakFigures& f) {
  return {{"rss_mib",
           {{"reference_t_s", f.rss_reference_t_s},
            {"reference", f.rss_reference_mib},
            {"end_t_s", f.rss_end_t_s},
            {"end", f.rss_end_mib},
            {"max_after_reference", f.rss_max_mib},
            {"growth_percent", f.rss_growth_percent}}},
          {"frame_time_ms",
           {{"window_s", f.check.timing_window_s},
            {"cpu_median_first_window", FiniteOrNull(f.frame_cpu_median_first_ms)},
            {"cpu_median_last_window", FiniteOrNull(f.frame_cpu_median_last_ms)},
            {"cpu_drift_percent", FiniteOrNull(f.frame_cpu_drift_percent)},
            {"wall_median_first_window", FiniteOrNull(f.frame_wall_median_first_ms)},
            {"wall_median_last_window", FiniteOrNull(f.frame_wall_median_last_ms)},
            {"wall_drift_percent", FiniteOrNull(f.frame_wall_drift_percent)}}}};
}

nlohmann::json SoakAcceptanceJson(const SoakFigures& f) {
  return {{"rss_growth_below_" + std::to_string(static_cast<int>(f.check.max_rss_growth_percent)) +
               "_percent",
           f.rss_growth_ok}};
}

}  // namespace aperture::experiments
