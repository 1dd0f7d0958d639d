#include "perception/io/frame_source_options_io.h"

#include <stdexcept>
#include <utility>
#include <vector>

namespace aperture::perception {
namespace {

const std::vector<std::pair<std::string, ColorMode>>& ColorModeNames() {
  static const std::vector<std::pair<std::string, ColorMode>> kNames = {
      {ToString(ColorMode::kGray), ColorMode::kGray},
      {ToString(ColorMode::kColor), ColorMode::kColor}};
  return kNames;
}

}  // namespace

void LoadParams(config::ParamReader& reader, FrameSourceOptions* options) {
  reader.ReadEnum("color_mode", &options->color_mode, ColorModeNames());
  reader.Read("fps", &options->fps);
  reader.Read("skip_bad_frames", &options->skip_bad_frames);
  reader.Read("camera_id", &options->camera_id);
  reader.Read("image_topic", &options->image_topic);
  reader.Read("imu_topic", &options->imu_topic);
  reader.RejectUnknownKeys();
  try {
    CheckFrameSourceOptions(*options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(reader.Where("fps") + ": " + reader.FullKey("fps") + ": " +
                                e.what());
  }
}

ColorMode ParseColorMode(const std::string& name) {
  for (const auto& [candidate, mode] : ColorModeNames()) {
    if (candidate == name) return mode;
  }
  throw std::invalid_argument("colour mode '" + name + "' is unknown; use gray or color");
}

}  // namespace aperture::perception
