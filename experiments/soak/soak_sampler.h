#pragma once
// The samples of aperture bench soak: every interval_s of simulated time, the process's resident
// memory and the per-frame cost over the interval (the wall and thread-CPU time from one camera
// frame to the next: everything the flight does per frame: dynamics, rendering, the autopilot).
//
//   SoakSampler sampler(10.0);
//   on every frame:  if (auto sample = sampler.OnFrame(t_s)) { ...write it... }
//   at the end:      if (auto sample = sampler.Finish(t_end_s)) { ... }
#include <functional>
#include <optional>
#include <vector>

namespace aperture::experiments {

// Simulated times closer than this are the same instant [s]: frame times are the vehicle's clock,
// a sum of 1 ms steps whose rounding reaches ~1e-8 s over an hour (a sample due at 570 s must
// not slip to the frame after 569.99999999).
inline constexpr double kSoakTimeTolS = 1e-4;

struct SoakSample {
  double t_s = 0.0;      // simulated time at the sample [s]
  double wall_s = 0.0;   // wall time since the first frame [s]
  double cpu_s = 0.0;    // thread CPU time since the first frame [s]
  double rss_mib = 0.0;  // resident memory then [MiB]
  int frames = 0;        // frame-to-frame times in the interval
  double frame_wall_median_ms = 0.0;
  double frame_wall_max_ms = 0.0;
  double frame_cpu_median_ms = 0.0;
  double frame_cpu_max_ms = 0.0;
};

class SoakSampler {
 public:
  // Clocks and memory: wall time [s], thread CPU time [s], resident memory [bytes]; by default
  // std::chrono::steady_clock and output/process_resources.h. Throws std::invalid_argument for
  // a non-positive or non-finite interval.
  struct Sources {
    std::function<double()> wall_s;
    std::function<double()> cpu_s;
    std::function<double()> rss_bytes;
  };
  explicit SoakSampler(double interval_s);
  SoakSampler(double interval_s, Sources sources);

  // A frame at simulated time t_s (increasing). The first frame starts the clocks; each later one
  // adds its time since the previous one to the interval. Returns the interval's sample once t_s
  // has reached the next multiple of interval_s (stamped t_s).
  std::optional<SoakSample> OnFrame(double t_s);
  // The last, partial interval at the end of the flight (t_s); none when it holds no frame.
  std::optional<SoakSample> Finish(double t_s);

 private:
  SoakSample Sample(double t_s);

  double interval_s_;
  Sources sources_;
  double next_sample_t_s_;
  bool started_ = false;
  double start_wall_s_ = 0.0, start_cpu_s_ = 0.0;
  double last_wall_s_ = 0.0, last_cpu_s_ = 0.0;
  std::vector<double> frame_wall_ms_, frame_cpu_ms_;  // this interval's (cleared per sample)
};

}  // namespace aperture::experiments
