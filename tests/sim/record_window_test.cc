// KeepLastWindow (SitlRunnerParams::record_window_s): a long record stays within about two
// windows and the last window is always whole (the SITL side: sitl_runner_test.cc).
#include "sim/sitl/record_window.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace aperture::sim {
namespace {

struct Stamped {
  double t_s = 0.0;
};

TEST(RecordWindow, KeepsBetweenOneAndTwoWindowsOfRecords) {
  std::vector<Stamped> records;
  std::size_t largest = 0;
  // 128 Hz for 100 s (times exact in binary), a 1 s window.
  for (int k = 0; k <= 12800; ++k) {
    const double t_s = k / 128.0;
    records.push_back({t_s});
    KeepLastWindow(&records, t_s, 1.0);
    largest = std::max(largest, records.size());
    ASSERT_LE(records.front().t_s, std::max(0.0, t_s - 1.0)) << "the last window is whole";
    ASSERT_GE(records.front().t_s, t_s - 2.0);
  }
  EXPECT_LE(largest, 2u * 128u + 1u);
  EXPECT_LE(records.capacity(), 512u);  // the vector stops growing with the flight
  std::vector<Stamped> all;
  for (int k = 0; k < 500; ++k) {
    all.push_back({0.01 * k});
    KeepLastWindow(&all, 0.01 * k, 0.0);  // 0: keep everything
  }
  EXPECT_EQ(all.size(), 500u);
}

}  // namespace
}  // namespace aperture::sim
