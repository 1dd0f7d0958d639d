#include "experiments/soak/soak_sampler.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "experiments/bench/sample_statistics.h"
#include "output/process_resources.h"

namespace aperture::experiments {
namespace {

constexpr double kBytesPerMib = 1024.0 * 1024.0;

double SteadyClockSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double MaxOf(const std::vector<double>& values) {
  return values.empty() ? std::nan("") : *std::max_element(values.begin(), values.end());
}

}  // namespace

SoakSampler::SoakSampler(double interval_s)
    : SoakSampler(interval_s, {SteadyClockSeconds, output::ThreadCpuSeconds,
                               [] { return output::ResidentSetBytes(); }}) {}

SoakSampler::SoakSampler(double interval_s, Sources sources)
    : interval_s_(interval_s), sources_(std::move(sources)), next_sample_t_s_(interval_s) {
  if (!std::isfinite(interval_s) || !(interval_s > 0.0)) {
    throw std::invalid_argument(
        "the soak's sampling interval must be a positive number of "
        "seconds, got " +
        std::to_string(interval_s));
  }
}

std::optional<SoakSample> SoakSampler::OnFrame(double t_s) {
  const double wall_s = sources_.wall_s();
  const double cpu_s = sources_.cpu_s();
  if (!started_) {
    started_ = true;
    start_wall_s_ = wall_s;
    start_cpu_s_ = cpu_s;
  } else {
    frame_wall_ms_.push_back(1e3 * (wall_s - last_wall_s_));
    frame_cpu_ms_.push_back(1e3 * (cpu_s - last_cpu_s_));
  }
  last_wall_s_ = wall_s;
  last_cpu_s_ = cpu_s;
  if (t_s + kSoakTimeTolS < next_sample_t_s_) return std::nullopt;
  while (next_sample_t_s_ <= t_s + kSoakTimeTolS) next_sample_t_s_ += interval_s_;
  return Sample(t_s);
}

std::optional<SoakSample> SoakSampler::Finish(double t_s) {
  if (frame_wall_ms_.empty()) return std::nullopt;
  return Sample(t_s);
}

SoakSample SoakSampler::Sample(double t_s) {
  SoakSample sample;
  sample.t_s = t_s;
  sample.wall_s = last_wall_s_ - start_wall_s_;
  sample.cpu_s = last_cpu_s_ - start_cpu_s_;
  sample.rss_mib = sources_.rss_bytes() / kBytesPerMib;
  sample.frames = static_cast<int>(frame_wall_ms_.size());
  sample.frame_wall_median_ms = UpperMedian(frame_wall_ms_);
  sample.frame_wall_max_ms = MaxOf(frame_wall_ms_);
  sample.frame_cpu_median_ms = UpperMedian(frame_cpu_ms_);
  sample.frame_cpu_max_ms = MaxOf(frame_cpu_ms_);
  frame_wall_ms_.clear();
  frame_cpu_ms_.clear();
  return sample;
}

}  // namespace aperture::experiments
