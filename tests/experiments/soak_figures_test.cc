// aperture bench soak's verdict on constructed samples: flat memory passes, a leak fails, the
// reference is minute 1 and the timing windows the first and last ten minutes; the sampler's
// intervals and per-frame medians from fake clocks.
#include "experiments/soak/soak_figures.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "experiments/soak/soak_sampler.h"

namespace aperture::experiments {
namespace {

// An hour sampled every 10 s: RSS rss_at(t), per-frame CPU median cpu_ms_at(t).
template <typename Rss, typename Cpu>
std::vector<SoakSample> Hour(Rss rss_at, Cpu cpu_ms_at) {
  std::vector<SoakSample> samples;
  for (int k = 1; k <= 360; ++k) {
    SoakSample s;
    s.t_s = 10.0 * k;
    s.rss_mib = rss_at(s.t_s);
    s.frames = 400;
    s.frame_cpu_median_ms = cpu_ms_at(s.t_s);
    s.frame_wall_median_ms = 2.0 * cpu_ms_at(s.t_s);
    samples.push_back(s);
  }
  return samples;
}

TEST(SoakFigures, FlatMemoryAfterTheWarmUpPasses) {
  // 100 MiB reached during the first minute (the warm-up is not counted), then flat +-0.5 MiB.
  const auto samples = Hour(
      [](double t) {
        return t < 60.0 ? t * 100.0 / 60.0 : 100.0 + 0.5 * ((static_cast<int>(t) / 10) % 2);
      },
      [](double) { return 4.0; });
  const SoakFigures f = ComputeSoakFigures(samples, SoakCheckParams{});
  EXPECT_DOUBLE_EQ(f.rss_reference_t_s, 60.0);
  EXPECT_DOUBLE_EQ(f.rss_reference_mib, 100.0);
  EXPECT_DOUBLE_EQ(f.rss_end_t_s, 3600.0);
  EXPECT_DOUBLE_EQ(f.rss_end_mib, 100.0);
  EXPECT_DOUBLE_EQ(f.rss_max_mib, 100.5);
  EXPECT_DOUBLE_EQ(f.rss_growth_percent, 0.0);
  EXPECT_TRUE(f.rss_growth_ok);
  EXPECT_DOUBLE_EQ(f.frame_cpu_drift_percent, 0.0);
  EXPECT_TRUE(SoakAcceptanceJson(f)["rss_growth_below_5_percent"].get<bool>());
}

TEST(SoakFigures, ALeakFailsTheCheck) {
  // 100 MiB at minute 1 growing 2 kiB per simulated second: +6.9 MiB (+6.9 %) by minute 60,
  // what an unbounded 200 Hz record of 10-byte entries would do.
  const auto samples =
      Hour([](double t) { return 100.0 + (t - 60.0) * 2.0 / 1024.0; }, [](double) { return 4.0; });
  const SoakFigures f = ComputeSoakFigures(samples, SoakCheckParams{});
  EXPECT_NEAR(f.rss_growth_percent, 3540.0 * 2.0 / 1024.0, 1e-9);
  EXPECT_FALSE(f.rss_growth_ok);
  EXPECT_FALSE(SoakAcceptanceJson(f)["rss_growth_below_5_percent"].get<bool>());
  // Just under the bound passes: the check is growth < 5 %.
  const auto slow =
      Hour([](double t) { return 100.0 + (t - 60.0) * 4.9 / 3540.0; }, [](double) { return 4.0; });
  EXPECT_TRUE(ComputeSoakFigures(slow, SoakCheckParams{}).rss_growth_ok);
}

TEST(SoakFigures, TimingDriftComparesTheFirstAndLastTenMinutes) {
  // Per-frame CPU 4 ms in the first ten minutes, 5 ms in the last ten, 100 ms in between (not
  // counted by either window).
  const auto samples = Hour([](double) { return 100.0; },
                            [](double t) { return t <= 600.0   ? 4.0
                                                  : t > 3000.0 ? 5.0
                                                               : 100.0; });
  const SoakFigures f = ComputeSoakFigures(samples, SoakCheckParams{});
  EXPECT_DOUBLE_EQ(f.frame_cpu_median_first_ms, 4.0);
  EXPECT_DOUBLE_EQ(f.frame_cpu_median_last_ms, 5.0);
  EXPECT_DOUBLE_EQ(f.frame_cpu_drift_percent, 25.0);
  EXPECT_DOUBLE_EQ(f.frame_wall_median_first_ms, 8.0);
  EXPECT_DOUBLE_EQ(f.frame_wall_drift_percent, 25.0);
}

TEST(SoakFigures, ShortRunsShrinkTheWindowsAndTooShortIsAnError) {
  const SoakCheckParams short_run = SoakCheckParamsFor(30.0);
  EXPECT_DOUBLE_EQ(short_run.rss_reference_s, 15.0);
  EXPECT_DOUBLE_EQ(short_run.timing_window_s, 15.0);
  const SoakCheckParams hour = SoakCheckParamsFor(3600.0);
  EXPECT_DOUBLE_EQ(hour.rss_reference_s, 60.0);
  EXPECT_DOUBLE_EQ(hour.timing_window_s, 600.0);
  std::vector<SoakSample> samples(2);
  samples[0].t_s = 10.0;
  samples[1].t_s = 20.0;
  EXPECT_THROW(ComputeSoakFigures(samples, SoakCheckParams{}), std::invalid_argument);
  samples[1].t_s = 10.0;
  EXPECT_THROW(ComputeSoakFigures(samples, SoakCheckParamsFor(20.0)), std::invalid_argument);
}

TEST(SoakSampler, SamplesEveryIntervalWithTheFrameTimesBetween) {
  // Fake clocks: frame n (every 25 ms simulated) ends at wall 3n ms and CPU n ms, except frame
  // 7, which takes 50 ms of wall time more; RSS counts its reads in MiB.
  double wall = 0.0, cpu = 0.0, rss = 0.0;
  SoakSampler sampler(
      0.1, {[&] { return wall; }, [&] { return cpu; }, [&] { return (rss += 1.0) * 1024 * 1024; }});
  std::vector<SoakSample> samples;
  for (int n = 0; n <= 10; ++n) {
    wall = 3e-3 * n + (n >= 7 ? 0.05 : 0.0);
    cpu = 1e-3 * n;
    if (auto sample = sampler.OnFrame(0.025 * n)) samples.push_back(*sample);
  }
  if (auto sample = sampler.Finish(0.25)) samples.push_back(*sample);
  ASSERT_EQ(samples.size(), 3u);  // t = 0.1, 0.2 and the partial interval to 0.25
  EXPECT_DOUBLE_EQ(samples[0].t_s, 0.1);
  EXPECT_EQ(samples[0].frames, 4);  // frames 1-4 (frame 0 starts the clocks)
  EXPECT_NEAR(samples[0].frame_wall_median_ms, 3.0, 1e-9);
  EXPECT_NEAR(samples[0].frame_cpu_max_ms, 1.0, 1e-9);
  EXPECT_NEAR(samples[0].wall_s, 0.012, 1e-12);
  EXPECT_DOUBLE_EQ(samples[0].rss_mib, 1.0);
  EXPECT_EQ(samples[1].frames, 4);  // frames 5-8; frame 7 took 53 ms
  EXPECT_NEAR(samples[1].frame_wall_max_ms, 53.0, 1e-9);
  EXPECT_NEAR(samples[1].frame_wall_median_ms, 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(samples[2].t_s, 0.25);
  EXPECT_EQ(samples[2].frames, 2);
  EXPECT_NEAR(samples[2].cpu_s, 0.010, 1e-12);
  EXPECT_FALSE(sampler.Finish(0.25).has_value());  // nothing since the last sample
  EXPECT_THROW(SoakSampler(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
