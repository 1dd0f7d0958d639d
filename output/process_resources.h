#pragma once
// What this process uses while it runs, for benches that watch it over a long run
// (aperture bench soak): resident memory and the calling thread's CPU time.
#include <string>

namespace aperture::output {

// The resident set size of this process [bytes]: the VmRSS line of /proc/self/status (Linux).
// std::runtime_error naming the file when it cannot be read or has no readable VmRSS line (a
// system without /proc: the figure is not available there).
double ResidentSetBytes();
// The same from a file in the format of /proc/<pid>/status ("VmRSS:    123456 kB").
double ResidentSetBytes(const std::string& status_path);

// CPU time of the calling thread [s] (CLOCK_THREAD_CPUTIME_ID): its cost on one core, whatever
// else the machine runs.
double ThreadCpuSeconds();

}  // namespace aperture::output
