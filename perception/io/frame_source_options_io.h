#pragma once
// Configuration description (Serialize, config/param_archive.h) of FrameSourceOptions, loaded by
// LoadParams(reader, &options) (config/yaml_read_archive.h) and dumped by config::DumpParams, and
// the colour mode parsed from a command-line word. Keys are the field names:
//
//   source:
//     color_mode: gray        # gray | color
//     fps: 0                  # Hz, 0 = unset
//     skip_bad_frames: false
//     camera_id: 0
//     image_topic: ""         # ROS bags: sensor_msgs/Image or CompressedImage topic
//     imu_topic: ""           # ROS bags: sensor_msgs/Imu topic, "" = none
//
// Absent keys keep the in-class defaults; unknown keys, a bad colour mode or a negative fps throw
// std::invalid_argument naming where the value is and what is expected.
#include <string>

#include "config/yaml_read_archive.h"
#include "perception/io/frame_source.h"

namespace aperture::perception {

const config::EnumNames<ColorMode>& ColorModeNames();  // "gray", "color"

template <typename Archive>
void Serialize(Archive* a, FrameSourceOptions* p) {
  a->Visit(APERTURE_NVP(p, color_mode), ColorModeNames());
  a->Visit(APERTURE_NVP(p, fps));
  a->Visit(APERTURE_NVP(p, skip_bad_frames));
  a->Visit(APERTURE_NVP(p, camera_id));
  a->Visit(APERTURE_NVP(p, image_topic));
  a->Visit(APERTURE_NVP(p, imu_topic));
}

// Validation hook of the loader (config::ValidateLoaded): CheckFrameSourceOptions.
inline void ValidateParams(const FrameSourceOptions& options) { CheckFrameSourceOptions(options); }

// "gray" -> kGray, "color" -> kColor; anything else throws std::invalid_argument listing both.
ColorMode ParseColorMode(const std::string& name);

}  // namespace aperture::perception
