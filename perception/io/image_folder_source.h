#pragma once
// ImageFolderSource: an image sequence stored as one file per frame in a folder.
//
// Files: regular files with extension .png .jpg .jpeg .pgm .ppm .pnm .bmp .tif .tiff (any case),
// hidden files and subfolders ignored, played in natural order of their names (natural_sort.h:
// frame2 < frame10). A EuRoC camera folder (`cam0/` holding `data.csv` and `data/`) may be given
// directly; its images are read from `data/`.
//
// Timestamps [s], first match wins (formats in timestamps.h):
//   1. `times.txt` in the image folder;
//   2. EuRoC `data.csv` in the image folder or its parent;
//   3. file names, when every name encodes a time (>= 16 digits = ns, "<s>.<frac>" = seconds);
//   4. options.fps: t_i = i / fps;
// otherwise the constructor throws, asking for --fps or a times.txt.
//
// Failure (see frame_source.h for the skip policy):
//   constructor: missing folder, no images, unreadable/malformed times.txt or data.csv, times.txt
//     line count != image count, a listed file that is missing or an image without a listed time
//     (skipped and recorded with skip_bad_frames), non-increasing times -> throws;
//   Next(): empty, corrupt or truncated file, or an image size different from the first good
//     frame's -> throws, or skips with skip_bad_frames. The first good frame sets the size, so if
//     it is the odd one out every later frame is reported (the messages name it).
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "perception/io/frame_source.h"
#include "perception/io/timestamps.h"

namespace aperture::perception {

class ImageFolderSource : public FrameSource {
 public:
  ImageFolderSource(const std::filesystem::path& folder, const FrameSourceOptions& options);

  std::optional<Frame> Next() override;
  std::string Describe() const override;
  std::optional<size_t> SizeHint() const override { return files_.size(); }

  // Files to be played, in order, and their times [s] (same size).
  const std::vector<std::filesystem::path>& Files() const { return files_; }
  const std::vector<double>& Times() const { return times_s_; }
  // Where the times came from: "times.txt", "data.csv", "file names" or "fps".
  const std::string& TimeSource() const { return time_source_; }

 private:
  void AssignTimes(const std::filesystem::path& image_folder);
  void AssignTimesFromTable(const TimestampTable& table, const std::filesystem::path& file,
                            const std::filesystem::path& image_folder);
  // Records the skip when options_.skip_bad_frames, else throws std::invalid_argument.
  void SkipOrThrow(const std::string& item, const std::string& reason);

  std::filesystem::path folder_;
  FrameSourceOptions options_;
  std::vector<std::filesystem::path> files_;
  std::vector<double> times_s_;
  std::string time_source_;
  size_t next_ = 0;
  cv::Size frame_size_;         // size of the first good frame; empty until then
  std::string first_file_;      // that frame's file, for size mismatch messages
};

}  // namespace aperture::perception
