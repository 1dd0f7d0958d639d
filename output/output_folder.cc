#include "output/output_folder.h"

#include <exception>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "output/atomic_file.h"

namespace aperture::output {

OutputFolder::OutputFolder(const std::string& directory)
    : directory_(directory), start_(std::chrono::steady_clock::now()) {
  if (directory.empty()) {
    throw std::invalid_argument("output folder path is empty; pass --out DIR");
  }
  std::error_code error;
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
  std::filesystem::remove(Path(kSummaryFileName), error);
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
  summary_["status"] = status == RunStatus::kOk ? "ok" : "failed";
  if (status == RunStatus::kFailed) {
    summary_["error"] = error;
  } else {
    summary_.erase("error");
  }
  summary_["wall_time_s"] = ElapsedSeconds();
  const std::string path = Path(kSummaryFileName);
  WriteFileAtomically(
      path, summary_.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return path;
}

void RunAndWriteSummary(OutputFolder& out, const std::function<void()>& body) {
  try {
    body();
  } catch (const std::exception& e) {
    out.WriteSummary(RunStatus::kFailed, e.what());
    throw;
  } catch (...) {
    out.WriteSummary(RunStatus::kFailed, "unknown exception");
    throw;
  }
  out.WriteSummary(RunStatus::kOk);
}

}  // namespace aperture::output
