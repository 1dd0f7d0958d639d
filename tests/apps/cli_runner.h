#pragma once
// Runs the built `aperture` binary for end-to-end CLI tests.
#include <nlohmann/json.hpp>
#include <string>

namespace aperture::apps::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

// Runs `command_line` through the shell (e.g. a script given the aperture binary).
CommandResult RunShellCommand(const std::string& command_line);

// Runs `aperture <arguments>` through the shell (arguments are passed verbatim).
CommandResult RunAperture(const std::string& arguments);

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
