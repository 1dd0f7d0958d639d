#pragma once
// OutputFolder: the `--out DIR` of one command. It owns summary.json, the figures of the run:
//
//   OutputFolder out(out_dir);                    // creates DIR (and parents), checks it is
//   writable out.summary()["inputs"]["sequence"] = path;   // fill as the run goes
//   ... write CSVs, report.html to out.Path("...") ...
//   out.WriteSummary(RunStatus::kOk);             // or kFailed with the error message
//
// summary.json is written atomically and always carries "status": "ok" | "failed" | "interrupted"
// (plus "error" when failed, and "signal": "SIGINT" | "SIGTERM" when interrupted, see
// output/interruption.h), "wall_time_s" and "files": the entries of the folder this run created
// (files and subfolders, sorted). A stale summary.json from an earlier run in the same folder is
// removed at construction, so a run that crashes before WriteSummary leaves no summary at all
// rather than an old one that looks complete.
//
// A folder is used only when it is new, empty, or holds nothing but the summary.json of a run
// that wrote no other file (a run that failed at its first check): an earlier run's outputs would
// otherwise sit beside the new ones. With `overwrite`, the files an earlier run created (its
// summary.json "files", or "outputs" for a summary without "files") are removed first; other files
// in the folder are left alone.
#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>

namespace aperture::output {

// kInterrupted: stopped early by SIGINT/SIGTERM (output/interruption.h); the outputs hold what was
// done until then.
enum class RunStatus { kOk, kFailed, kInterrupted };

// The path is taken: a file, or a folder holding an earlier run's outputs (or files of no
// aperture run) while `overwrite` is off.
class FolderInUseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFolder {
 public:
  // std::runtime_error naming `directory` when it cannot be created or written to;
  // FolderInUseError when it is a file, holds other files and `overwrite` is false, or (with
  // `overwrite`) files no aperture run recorded.
  explicit OutputFolder(const std::string& directory, bool overwrite = false);

  // `directory`/`name`; `name` may contain subfolders, which the caller creates.
  std::string Path(const std::string& name) const;
  const std::string& directory() const { return directory_; }

  nlohmann::json& summary() { return summary_; }
  const nlohmann::json& summary() const { return summary_; }
  // Seconds since the folder was opened (the run's wall time so far).
  double ElapsedSeconds() const;

  // Writes summary.json (atomically). `error` is required for kFailed, ignored for kOk, and
  // recorded for kInterrupted when given (what the interruption cut short).
  // Returns the path written.
  std::string WriteSummary(RunStatus status, const std::string& error = "");

  static constexpr const char* kSummaryFileName = "summary.json";

 private:
  std::string directory_;
  nlohmann::json summary_ = nlohmann::json::object();
  std::chrono::steady_clock::time_point start_;
  std::set<std::string> entries_before_;  // left by --overwrite: not this run's
};

// Runs `body` and always leaves a summary: "ok" when it returns, "failed" with the exception's
// message when it throws (the exception is then rethrown for main() to report and turn into an
// exit code); "interrupted" in either case once SIGINT/SIGTERM asked to stop
// (InterruptionRequested(), output/interruption.h), with the error when it threw.
//   OutputFolder out(out_dir);
//   RunAndWriteSummary(out, [&] { ...the command... });
void RunAndWriteSummary(OutputFolder& out, const std::function<void()>& body);

}  // namespace aperture::output
