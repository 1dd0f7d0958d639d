#pragma once
// AtomicFile: write a file under a temporary name ("<path>.tmp") and rename it to `path` only when
// the writing finished, so a crash or an exception never leaves a file that looks complete.
//
//   AtomicFile file(folder.Path("poses.csv"));
//   file.stream() << ...;
//   file.Commit();            // flush, check, rename; throws std::runtime_error naming the path
//
// Destroying an uncommitted AtomicFile during stack unwinding (an exception is in flight) removes
// the temporary file; destroying it on a normal scope exit commits it (errors go to stderr, since
// a destructor cannot throw — call Commit() to get them as exceptions).
#include <fstream>
#include <string>

namespace aperture::output {

class AtomicFile {
 public:
  // Opens "<path>.tmp" for writing (binary). std::runtime_error naming the path when it cannot.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return stream_; }
  // Flushes, closes and renames the temporary file to path(). Idempotent.
  void Commit();
  // Closes and deletes the temporary file; path() is left untouched. Idempotent.
  void Discard();

  const std::string& path() const { return path_; }
  std::string temporary_path() const { return path_ + ".tmp"; }
  bool committed() const { return committed_; }

 private:
  std::string path_;
  std::ofstream stream_;
  bool committed_ = false;
  bool discarded_ = false;
  int uncaught_exceptions_at_open_;
};

// Writes `content` to `path` through an AtomicFile.
void WriteFileAtomically(const std::string& path, const std::string& content);

}  // namespace aperture::output
