#include "perception/io/image_folder_source.h"

#include <fstream>
#include <map>
#include <stdexcept>

#include "config/usage_error.h"
#include "perception/io/image_file_reader.h"
#include "perception/io/natural_sort.h"

namespace aperture::perception {
namespace fs = std::filesystem;
namespace {

constexpr const char* kSkipHint = " (or skip such frames with --skip-bad-frames)";
constexpr const char* kImageExtensions = ".png .jpg .jpeg .pgm .ppm .pnm .bmp .tif .tiff";

// Image files directly in `folder` (no hidden files, no subfolders), in natural order. A symbolic
// link is listed even when its target is missing: reading it then fails naming the file (or skips
// it with --skip-bad-frames), rather than the frame vanishing and shifting every later --fps time.
std::vector<fs::path> ListImages(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if ((entry.is_regular_file() || entry.is_symlink()) && name[0] != '.' &&
        HasImageExtension(entry.path())) {
      names.push_back(name);
    }
  }
  NaturalSort(names);
  std::vector<fs::path> files;
  files.reserve(names.size());
  for (const std::string& name : names) files.push_back(folder / name);
  return files;
}

std::ifstream OpenText(const fs::path& file) {
  std::ifstream in(file);
  if (!in) {
    throw std::runtime_error("cannot read '" + file.string() + "'; check its permissions");
  }
  return in;
}

std::string SizeText(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// "seq/" -> "seq", so that parent_path() is the parent folder.
fs::path WithoutTrailingSeparator(const fs::path& folder) {
  return folder.has_filename() || !folder.has_parent_path() ? folder : folder.parent_path();
}

}  // namespace

ImageFolderSource::ImageFolderSource(const fs::path& folder, const FrameSourceOptions& options)
    : folder_(WithoutTrailingSeparator(folder)), options_(options) {
  CheckFrameSourceOptions(options);
  if (!fs::exists(folder_)) {
    throw std::runtime_error("image folder '" + folder_.string() +
                             "' does not exist; check the path given as the frame source");
  }
  if (!fs::is_directory(folder_)) {
    throw std::invalid_argument("'" + folder_.string() +
                                "' is not a folder; give the folder that holds the images");
  }
  fs::path image_folder = folder_;
  files_ = ListImages(folder_);
  // A EuRoC camera folder (cam0/ with data.csv and data/) may be given instead of cam0/data/.
  if (files_.empty() && fs::is_directory(folder_ / "data") && fs::exists(folder_ / "data.csv")) {
    image_folder = folder_ / "data";
    files_ = ListImages(image_folder);
  }
  if (files_.empty()) {
    throw std::runtime_error("image folder '" + folder_.string() + "' contains no images (" +
                             kImageExtensions +
                             "); give the folder that directly holds the frame files");
  }
  AssignTimes(image_folder);
}

void ImageFolderSource::AssignTimes(const fs::path& image_folder) {
  const fs::path times_txt = image_folder / "times.txt";
  fs::path data_csv = image_folder / "data.csv";
  if (!fs::exists(data_csv)) data_csv = fs::absolute(image_folder).parent_path() / "data.csv";

  if (fs::exists(times_txt)) {
    time_source_ = "times.txt";
    std::ifstream in = OpenText(times_txt);
    const TimestampTable table = ParseTimesTxt(in, times_txt.string());
    if (!table.names.empty()) {
      AssignTimesFromTable(table, times_txt, image_folder);
    } else if (table.t_s.size() != files_.size()) {
      throw std::invalid_argument(
          "'" + times_txt.string() + "' has " + std::to_string(table.t_s.size()) +
          " timestamps but the folder has " + std::to_string(files_.size()) +
          " images; write one time [s] per image in natural file order (first " +
          files_.front().filename().string() + ", last " + files_.back().filename().string() +
          ") or '<file name> <t>' lines");
    } else {
      times_s_ = table.t_s;
    }
  } else if (fs::exists(data_csv)) {
    time_source_ = "data.csv";
    std::ifstream in = OpenText(data_csv);
    AssignTimesFromTable(ParseEurocDataCsv(in, data_csv.string()), data_csv, image_folder);
  } else {
    std::vector<double> from_names;
    for (const fs::path& file : files_) {
      const std::optional<double> t_s = TimestampFromFileName(file.filename().string());
      if (!t_s) break;
      from_names.push_back(*t_s);
    }
    if (from_names.size() == files_.size()) {
      time_source_ = "file names";
      times_s_ = from_names;
    } else if (options_.fps > 0.0) {
      time_source_ = "fps";
      for (size_t i = 0; i < files_.size(); ++i) {
        times_s_.push_back(static_cast<double>(i) / options_.fps);
      }
    } else {
      // The missing option is the mistake (the folder is fine): a usage error, exit 2.
      throw config::UsageError(
          "image folder '" + folder_.string() +
          "' has no timestamps: pass --fps <rate> (frame rate in Hz), or add a times.txt there "
          "(one time in seconds per image in natural file order, or '<file name> <t>' lines), or "
          "a EuRoC data.csv, or name the files by nanosecond timestamp");
    }
  }
  std::vector<std::string> labels;
  labels.reserve(files_.size());
  for (const fs::path& file : files_) labels.push_back("'" + file.filename().string() + "'");
  CheckStrictlyIncreasing(
      times_s_, labels,
      "image folder '" + folder_.string() + "' (times from " + time_source_ + ")");
}

void ImageFolderSource::AssignTimesFromTable(const TimestampTable& table, const fs::path& file,
                                             const fs::path& image_folder) {
  std::map<std::string, size_t> entry_of_name;
  for (size_t i = 0; i < table.names.size(); ++i) {
    const auto [it, inserted] = entry_of_name.emplace(table.names[i], i);
    if (!inserted) {
      throw std::invalid_argument(
          "'" + file.string() + "' line " + std::to_string(table.line_numbers[i]) + " lists '" +
          table.names[i] + "' again (first on line " +
          std::to_string(table.line_numbers[it->second]) + "); remove one of the lines");
    }
  }
  std::vector<fs::path> timed_files;
  std::vector<bool> entry_used(table.names.size(), false);
  for (const fs::path& image : files_) {
    auto it = entry_of_name.find(image.filename().string());
    if (it == entry_of_name.end()) it = entry_of_name.find(image.stem().string());
    if (it == entry_of_name.end()) {
      SkipOrThrow(image.string(), "has no timestamp in '" + file.string() +
                                      "'; add a line for it or remove the image");
      continue;
    }
    timed_files.push_back(image);
    times_s_.push_back(table.t_s[it->second]);
    entry_used[it->second] = true;
  }
  for (size_t i = 0; i < table.names.size(); ++i) {
    if (entry_used[i]) continue;
    SkipOrThrow((image_folder / table.names[i]).string(),
                "is listed in '" + file.string() + "' line " +
                    std::to_string(table.line_numbers[i]) +
                    " but is not an image file in the folder; restore the file or remove the line");
  }
  files_ = timed_files;
  if (files_.empty()) {
    throw std::invalid_argument("no image in '" + image_folder.string() + "' has a time in '" +
                                file.string() + "'; check that the file names match");
  }
}

void ImageFolderSource::SkipOrThrow(const std::string& item, const std::string& reason) {
  if (options_.skip_bad_frames) {
    RecordSkip(item, reason);
    return;
  }
  throw std::invalid_argument("'" + item + "' " + reason + kSkipHint);
}

std::optional<Frame> ImageFolderSource::Next() {
  while (next_ < files_.size()) {
    const size_t i = next_++;
    const fs::path& file = files_[i];
    cv::Mat image;
    try {
      image = ReadImageFile(file, options_.color_mode);
    } catch (const std::runtime_error& e) {
      if (!options_.skip_bad_frames) {
        throw std::runtime_error(std::string(e.what()) + kSkipHint);
      }
      RecordSkip(file.string(), e.what());
      continue;
    }
    if (frame_size_.empty()) {
      frame_size_ = image.size();
      first_file_ = file.filename().string();
    } else if (image.size() != frame_size_) {
      SkipOrThrow(file.string(), "is " + SizeText(image.size()) + " but the sequence started " +
                                     SizeText(frame_size_) + " (" + first_file_ +
                                     "); all frames must have one size: resize or remove it");
      continue;
    }
    Frame frame;
    frame.t_s = times_s_[i];
    frame.camera_id = options_.camera_id;
    frame.index = static_cast<int>(i);
    frame.image = image;
    return frame;
  }
  return std::nullopt;
}

std::string ImageFolderSource::Describe() const {
  std::string text = "image folder '" + folder_.string() + "'";
  if (!time_source_.empty()) {
    text += " (" + std::to_string(files_.size()) + " images, " + ToString(options_.color_mode) +
            ", times from " + time_source_ + ")";
  }
  return text;
}

}  // namespace aperture::perception
