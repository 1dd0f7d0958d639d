#pragma once
// Loading FrameSourceOptions from configuration (config::ParamReader, STYLE.md 6) and parsing the
// colour mode from a command-line word. Keys are the field names:
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

#include "config/param_reader.h"
#include "perception/io/frame_source.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, FrameSourceOptions* options);

// "gray" -> kGray, "color" -> kColor; anything else throws std::invalid_argument listing both.
ColorMode ParseColorMode(const std::string& name);

}  // namespace aperture::perception
