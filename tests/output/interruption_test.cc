// output/interruption.h: the handlers turn the first SIGINT/SIGTERM into the flag (raised for real
// in this process), give the signals back their default action for a second one, keep an ignored
// signal ignored and restore what they replaced; RunAndWriteSummary records "interrupted".
#include "output/interruption.h"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "output/output_folder.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::output {
namespace {

// The current action of `signal_number`.
void (*ActionOf(int signal_number))(int) {
  struct sigaction current {};
  sigaction(signal_number, nullptr, &current);
  return current.sa_handler;
}

class InterruptionTest : public aperture::testing::TempDirectoryTest {
 protected:
  void SetUp() override {
    TempDirectoryTest::SetUp();
    ClearInterruption();
  }
  void TearDown() override {
    ClearInterruption();
    TempDirectoryTest::TearDown();
  }

  nlohmann::json ReadSummary() const {
    std::ifstream file(directory_ / "out" / OutputFolder::kSummaryFileName);
    return nlohmann::json::parse(file);
  }
};

TEST_F(InterruptionTest, FirstSignalSetsTheFlagAndRestoresDefaultsForTheSecond) {
  std::signal(SIGINT, SIG_DFL);  // as in an interactive shell (a background job ignores SIGINT)
  std::signal(SIGTERM, SIG_DFL);
  {
    InterruptionHandlers handlers;
    EXPECT_NE(ActionOf(SIGINT), SIG_DFL);
    EXPECT_NE(ActionOf(SIGTERM), SIG_DFL);
    EXPECT_FALSE(InterruptionRequested());
    std::raise(SIGTERM);  // would end this test process without the handler
    EXPECT_TRUE(InterruptionRequested());
    EXPECT_EQ(InterruptionSignal(), SIGTERM);
    EXPECT_EQ(InterruptedExitCode(), 143);
    // A second signal, of either kind, gets the default action: it ends the process at once.
    EXPECT_EQ(ActionOf(SIGINT), SIG_DFL);
    EXPECT_EQ(ActionOf(SIGTERM), SIG_DFL);
  }
  EXPECT_EQ(InterruptionSignal(), SIGTERM);  // the process still stops
}

TEST_F(InterruptionTest, HandlersAreRestoredAndAnIgnoredSignalStaysIgnored) {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_DFL);
  {
    InterruptionHandlers outer;
    InterruptionHandlers inner;  // nested: the outer one installed
    EXPECT_EQ(ActionOf(SIGINT), SIG_IGN);
    EXPECT_NE(ActionOf(SIGTERM), SIG_DFL);
    std::raise(SIGINT);  // ignored, as the process was started
    EXPECT_FALSE(InterruptionRequested());
  }
  EXPECT_EQ(ActionOf(SIGINT), SIG_IGN);
  EXPECT_EQ(ActionOf(SIGTERM), SIG_DFL);  // restored
  std::signal(SIGINT, SIG_DFL);
  {
    InterruptionHandlers handlers;
    std::raise(SIGINT);
    EXPECT_EQ(InterruptedExitCode(), 130);
  }
}

TEST_F(InterruptionTest, RunAndWriteSummaryRecordsTheInterruption) {
  OutputFolder out((directory_ / "out").string());
  RunAndWriteSummary(out, [&] {
    out.summary()["frames"] = 12;
    RequestInterruption(SIGINT);  // as Ctrl-C during the frame loop
  });
  nlohmann::json summary = ReadSummary();
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["signal"], "SIGINT");
  EXPECT_EQ(summary["frames"], 12);
  EXPECT_FALSE(summary.contains("error"));

  // An error after the signal (e.g. no frame at all) is kept, the status stays "interrupted".
  EXPECT_THROW(RunAndWriteSummary(
                   out, [] { throw std::runtime_error("interrupted before the first frame"); }),
               std::runtime_error);
  summary = ReadSummary();
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["error"], "interrupted before the first frame");

  ClearInterruption();
  RunAndWriteSummary(out, [] {});
  summary = ReadSummary();
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_FALSE(summary.contains("signal"));
  EXPECT_FALSE(summary.contains("error"));
}

}  // namespace
}  // namespace aperture::output
