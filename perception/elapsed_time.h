#pragma once
// Wall time elapsed on the steady clock since `start`: the stage timings the front ends and the
// frame graph report (one definition for every file that times a stage).
#include <chrono>

namespace aperture::perception {

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace aperture::perception
