#include "output/process_resources.h"

#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace aperture::output {

double ResidentSetBytes() { return ResidentSetBytes("/proc/self/status"); }

double ResidentSetBytes(const std::string& status_path) {
  std::ifstream status(status_path);
  if (!status) {
    throw std::runtime_error("cannot read " + status_path +
                             " for the resident memory (VmRSS); it needs Linux's /proc");
  }
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) != 0) continue;
    std::istringstream fields(line.substr(6));
    double kib = 0.0;
    std::string unit;
    if (fields >> kib >> unit && unit == "kB" && kib > 0.0) return kib * 1024.0;
    throw std::runtime_error(status_path + ": unreadable VmRSS line '" + line +
                             "' (expected 'VmRSS: <number> kB')");
  }
  throw std::runtime_error(status_path +
                           " has no VmRSS line: the resident memory is not available");
}

double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace aperture::output
