#include "perception/io/open_frame_source.h"

#include <filesystem>
#include <stdexcept>

#include "perception/io/camera_device_source.h"
#include "perception/io/image_file_reader.h"
#include "perception/io/image_folder_source.h"
#include "perception/io/rosbag_source.h"
#include "perception/io/video_file_source.h"

namespace aperture::perception {
namespace fs = std::filesystem;
namespace {

bool HoldsImages(const fs::path& folder) {
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file() && HasImageExtension(entry.path())) return true;
  }
  return false;
}

}  // namespace

std::unique_ptr<FrameSource> OpenFrameSource(const std::string& spec,
                                             const FrameSourceOptions& options) {
  const std::string kCameraPrefix = "camera:";
  if (spec.rfind(kCameraPrefix, 0) == 0) {
    const std::string number = spec.substr(kCameraPrefix.size());
    const bool all_digits = !number.empty() && number.size() <= 6 &&
                            number.find_first_not_of("0123456789") == std::string::npos;
    if (!all_digits) {
      throw std::invalid_argument("frame source '" + spec +
                                  "' is not a camera spec; write camera:<N> with a device index "
                                  "N >= 0, e.g. camera:0");
    }
    return std::make_unique<CameraDeviceSource>(std::stoi(number), options);
  }
  if (spec.empty()) {
    throw std::invalid_argument(
        "empty frame source; give an image folder, a video file or camera:<N>");
  }
  const fs::path path(spec);
  if (!fs::exists(path)) {
    throw std::runtime_error("frame source '" + spec +
                             "' does not exist; give an image folder, a video file, a ROS bag "
                             "or camera:<N>");
  }
  if (fs::is_directory(path)) {
    // A dataset folder (as `aperture render` writes) keeps its frames in images/.
    const fs::path images = path / "images";
    if (!HoldsImages(path) && fs::is_directory(images) && HoldsImages(images)) {
      return std::make_unique<ImageFolderSource>(images, options);
    }
    return std::make_unique<ImageFolderSource>(path, options);
  }
  if (HasImageExtension(path)) {
    throw std::invalid_argument("frame source '" + spec +
                                "' is a single image; give the folder that holds the sequence (" +
                                path.parent_path().string() + ")");
  }
  if (path.extension() == ".bag") return std::make_unique<RosbagSource>(path, options);
  return std::make_unique<VideoFileSource>(path, options);
}

}  // namespace aperture::perception
