#pragma once
// Runs the built `aperture` binary for end-to-end CLI tests.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace aperture::apps::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

// Runs `command_line` through the shell (e.g. a script given the aperture binary).
CommandResult RunShellCommand(const std::string& command_line);

// Runs `aperture <arguments>` through the shell (arguments are passed verbatim).
CommandResult RunAperture(const std::string& arguments);

// `aperture <arguments>` running as a child process (no shell between: signals reach it), its
// stdout and stderr on a pseudo-terminal as in an interactive shell (so the progress bar draws).
// The destructor kills (SIGKILL) and reaps a child still running.
//
//   ApertureProcess sim({"sim", "gap", "--duration", "600", "--out", out});
//   ASSERT_TRUE(sim.WaitUntil([&] { return fs::exists(out / "sim.partial.mp4"); }, 60.0));
//   sim.Signal(SIGINT);
//   EXPECT_EQ(sim.Wait(60.0), 130) << sim.output();
class ApertureProcess {
 public:
  explicit ApertureProcess(const std::vector<std::string>& arguments);
  ~ApertureProcess();
  ApertureProcess(const ApertureProcess&) = delete;
  ApertureProcess& operator=(const ApertureProcess&) = delete;

  // Reads the output while polling `condition` (every ~20 ms) until it holds: true; false when
  // `timeout_s` passed or the process exited first.
  bool WaitUntil(const std::function<bool()>& condition, double timeout_s);
  void Signal(int signal_number);
  // Waits for the exit, reading the output: the exit code, 128 + N when signal N ended the
  // process (as a shell reports it), -1 when it is still running after `timeout_s`.
  int Wait(double timeout_s);
  // stdout and stderr so far.
  const std::string& output() const { return output_; }

 private:
  void ReadOutput(int timeout_ms);
  bool Reap(int options);

  int pid_ = -1;
  int terminal_ = -1;  // the pseudo-terminal's master side
  int exit_code_ = -1;
  bool exited_ = false;
  std::string output_;
};

// The JSON document in `path` (e.g. a run's summary.json).
nlohmann::json ReadJson(const std::string& path);

// Number of lines in the text file `path`.
std::size_t CountLines(const std::string& path);

// A fresh, empty folder under the system temp directory, removed by the destructor.
class TempFolder {
 public:
  explicit TempFolder(const std::string& stem);
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace aperture::apps::testing
