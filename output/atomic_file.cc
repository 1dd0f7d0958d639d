#include "output/atomic_file.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

namespace aperture::output {

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), uncaught_exceptions_at_open_(std::uncaught_exceptions()) {
  stream_.open(temporary_path(), std::ios::binary | std::ios::trunc);
  if (!stream_) {
    throw std::runtime_error("cannot write '" + temporary_path() +
                             "'; check that the output folder exists and is writable");
  }
}

AtomicFile::~AtomicFile() {
  if (committed_ || discarded_) return;
  if (std::uncaught_exceptions() > uncaught_exceptions_at_open_) {
    Discard();
    return;
  }
  try {
    Commit();
  } catch (const std::exception& e) {
    std::cerr << "aperture: " << e.what() << "\n";
    Discard();
  }
}

void AtomicFile::Commit() {
  if (committed_) return;
  if (discarded_) throw std::logic_error("AtomicFile::Commit after Discard for '" + path_ + "'");
  stream_.flush();
  const bool write_ok = static_cast<bool>(stream_);
  stream_.close();
  if (!write_ok || stream_.fail()) {
    Discard();
    throw std::runtime_error("writing '" + path_ + "' failed (disk full or folder removed?)");
  }
  std::error_code error;
  std::filesystem::rename(temporary_path(), path_, error);
  if (error) {
    Discard();
    throw std::runtime_error("cannot rename '" + temporary_path() + "' to '" + path_ +
                             "': " + error.message());
  }
  committed_ = true;
}

void AtomicFile::Discard() {
  if (committed_ || discarded_) return;
  discarded_ = true;
  if (stream_.is_open()) stream_.close();
  std::error_code ignored;  // nothing to do if it is already gone
  std::filesystem::remove(temporary_path(), ignored);
}

void WriteFileAtomically(const std::string& path, const std::string& content) {
  AtomicFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.Commit();
}

}  // namespace aperture::output
