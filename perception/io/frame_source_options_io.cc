#include "perception/io/frame_source_options_io.h"

#include <stdexcept>

namespace aperture::perception {

const config::EnumNames<ColorMode>& ColorModeNames() {
  static const config::EnumNames<ColorMode> kNames = {
      {ToString(ColorMode::kGray), ColorMode::kGray},
      {ToString(ColorMode::kColor), ColorMode::kColor}};
  return kNames;
}

ColorMode ParseColorMode(const std::string& name) {
  for (const auto& [candidate, mode] : ColorModeNames()) {
    if (candidate == name) return mode;
  }
  throw std::invalid_argument("colour mode '" + name + "' is unknown; use gray or color");
}

}  // namespace aperture::perception
