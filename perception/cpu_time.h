#pragma once
// CPU time, for stage costs that do not depend on what else the machine runs (wall time counts
// the other processes): one definition for every file that times a stage on the CPU.
//   ThreadCpuSeconds   the calling thread's CPU time [s]: the cost of single-threaded work
//   ProcessCpuSeconds  every thread's CPU time [s]: the cost of work split over oneTBB's workers
//                      (the renderer's rows), exact while nothing else runs in the process
// ScopedCpuTimer adds the process CPU time spent during its lifetime to *sum_s (a stage of a
// profile; nullptr: no-op). Each reading is one clock_gettime system call (~0.2-0.5 us).
#include <time.h>

namespace aperture::perception {

inline double CpuClockSeconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double ThreadCpuSeconds() { return CpuClockSeconds(CLOCK_THREAD_CPUTIME_ID); }
inline double ProcessCpuSeconds() { return CpuClockSeconds(CLOCK_PROCESS_CPUTIME_ID); }

class ScopedCpuTimer {
 public:
  explicit ScopedCpuTimer(double* sum_s)
      : sum_s_(sum_s), start_s_(sum_s != nullptr ? ProcessCpuSeconds() : 0.0) {}
  ~ScopedCpuTimer() {
    if (sum_s_ != nullptr) *sum_s_ += ProcessCpuSeconds() - start_s_;
  }
  ScopedCpuTimer(const ScopedCpuTimer&) = delete;
  ScopedCpuTimer& operator=(const ScopedCpuTimer&) = delete;

 private:
  double* sum_s_;
  double start_s_;
};

}  // namespace aperture::perception
