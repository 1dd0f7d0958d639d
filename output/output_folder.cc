#include "output/output_folder.h"

#include <csignal>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "output/atomic_file.h"
#include "output/interruption.h"

namespace aperture::output {

namespace {

namespace fs = std::filesystem;

const char* RunStatusName(RunStatus status) {
  switch (status) {
    case RunStatus::kOk:
      return "ok";
    case RunStatus::kFailed:
      return "failed";
    case RunStatus::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string SignalName(int signal_number) {
  if (signal_number == SIGINT) return "SIGINT";
  if (signal_number == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal_number);
}

std::set<std::string> EntriesOf(const fs::path& directory) {
  std::set<std::string> entries;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    entries.insert(entry.path().filename().string());
  }
  return entries;
}

// A name an earlier summary.json recorded, reduced to the folder entry holding it ("images" for
// "images/times.txt"); empty when it does not name an entry inside the folder.
std::string EntryOfRecordedName(const std::string& name) {
  const fs::path path(name);
  if (path.empty() || path.is_absolute()) return "";
  const std::string first = path.begin()->string();
  return first == "." || first == ".." ? "" : first;
}

void CollectOutputNames(const nlohmann::json& outputs, std::set<std::string>* names) {
  if (outputs.is_string()) {
    const std::string entry = EntryOfRecordedName(outputs.get<std::string>());
    if (!entry.empty()) names->insert(entry);
  } else if (outputs.is_object() || outputs.is_array()) {
    for (const nlohmann::json& value : outputs) CollectOutputNames(value, names);
  }
}

// The entries the earlier run in `directory` created, from its summary.json; nullopt when there is
// none (or it is unreadable): then the folder's files are not an aperture run's.
std::optional<std::set<std::string>> RecordedEntries(const fs::path& directory) {
  std::ifstream file(directory / OutputFolder::kSummaryFileName);
  if (!file) return std::nullopt;
  const nlohmann::json summary = nlohmann::json::parse(file, nullptr, /*allow_exceptions=*/false);
  if (!summary.is_object()) return std::nullopt;
  std::set<std::string> entries;
  if (summary.contains("files")) {
    CollectOutputNames(summary["files"], &entries);
  } else if (summary.contains("outputs")) {  // written before summaries listed "files"
    CollectOutputNames(summary["outputs"], &entries);
  }
  entries.erase(OutputFolder::kSummaryFileName);
  return entries;
}

// Refuses a folder holding another run's outputs (or foreign files), or with `overwrite` removes
// what the earlier run created. Leaves the folder without a summary.json.
void ClaimFolder(const fs::path& directory, bool overwrite) {
  std::set<std::string> entries = EntriesOf(directory);
  const std::optional<std::set<std::string>> recorded = RecordedEntries(directory);
  entries.erase(OutputFolder::kSummaryFileName);
  const std::string where = "output folder '" + directory.string() + "'";
  if (!overwrite) {
    if (!entries.empty()) {
      throw FolderInUseError(where + " is not empty (" + *entries.begin() +
                             (entries.size() > 1 ? ", ..." : "") +
                             "); pass --overwrite to replace an earlier run's outputs, or choose a "
                             "new --out");
    }
  } else if (!recorded && !entries.empty()) {
    throw FolderInUseError(where +
                           " holds files but no summary.json of an earlier aperture run, so "
                           "--overwrite does not know what to replace; empty it or choose a new "
                           "--out");
  } else if (recorded) {
    for (const std::string& entry : *recorded) {
      std::error_code error;
      fs::remove_all(directory / entry, error);
      if (error) {
        throw std::runtime_error("cannot remove '" + (directory / entry).string() +
                                 "' of the earlier run: " + error.message() +
                                 "; remove it yourself or choose a new --out");
      }
    }
  }
  std::error_code error;
  fs::remove(directory / OutputFolder::kSummaryFileName, error);
}

}  // namespace

OutputFolder::OutputFolder(const std::string& directory, bool overwrite)
    : directory_(directory), start_(std::chrono::steady_clock::now()) {
  if (directory.empty()) {
    throw std::invalid_argument("output folder path is empty; pass --out DIR");
  }
  std::error_code error;
  if (std::filesystem::exists(directory_, error) && !std::filesystem::is_directory(directory_)) {
    throw FolderInUseError("output folder '" + directory_ +
                           "' is a file, not a folder; choose another --out");
  }
  std::filesystem::create_directories(directory_, error);
  if (error || !std::filesystem::is_directory(directory_)) {
    throw std::runtime_error("cannot create output folder '" + directory_ + "'" +
                             (error ? ": " + error.message() : ": a file is in the way") +
                             "; choose another --out");
  }
  // Probe by writing, which also catches read-only mounts that permission bits do not show.
  const std::string probe = Path(".write_probe");
  try {
    WriteFileAtomically(probe, "");
  } catch (const std::runtime_error&) {
    throw std::runtime_error("output folder '" + directory_ +
                             "' is not writable; fix its permissions or choose another --out");
  }
  std::filesystem::remove(probe, error);
  ClaimFolder(directory_, overwrite);
  entries_before_ = EntriesOf(directory_);
}

std::string OutputFolder::Path(const std::string& name) const {
  return (std::filesystem::path(directory_) / name).string();
}

double OutputFolder::ElapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string OutputFolder::WriteSummary(RunStatus status, const std::string& error) {
  if (status == RunStatus::kFailed && error.empty()) {
    throw std::invalid_argument("WriteSummary(kFailed) needs an error message for summary.json");
  }
  summary_["status"] = RunStatusName(status);
  if (status != RunStatus::kOk && !error.empty()) {
    summary_["error"] = error;
  } else {
    summary_.erase("error");
  }
  if (status == RunStatus::kInterrupted) {
    summary_["signal"] = SignalName(InterruptionSignal());
  } else {
    summary_.erase("signal");
  }
  summary_["wall_time_s"] = ElapsedSeconds();
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& entry : EntriesOf(directory_)) {
    if (entry != kSummaryFileName && entries_before_.count(entry) == 0) files.push_back(entry);
  }
  summary_["files"] = files;
  const std::string path = Path(kSummaryFileName);
  WriteFileAtomically(
      path, summary_.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return path;
}

void RunAndWriteSummary(OutputFolder& out, const std::function<void()>& body) {
  const auto failed = [] {
    return InterruptionRequested() ? RunStatus::kInterrupted : RunStatus::kFailed;
  };
  try {
    body();
  } catch (const std::exception& e) {
    out.WriteSummary(failed(), e.what());
    throw;
  } catch (...) {
    out.WriteSummary(failed(), "unknown exception");
    throw;
  }
  out.WriteSummary(InterruptionRequested() ? RunStatus::kInterrupted : RunStatus::kOk);
}

}  // namespace aperture::output
