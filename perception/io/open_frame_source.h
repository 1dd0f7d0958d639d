#pragma once
// OpenFrameSource: builds the FrameSource a command-line spec names, for
// `aperture run --source <spec> [--fps F] [--skip-bad-frames] [--color]`.
//
//   camera:<N>        CameraDeviceSource on device index N (N >= 0)
//   <folder>          ImageFolderSource (see image_folder_source.h for timestamps); a dataset
//                     folder without images of its own but with an images/ subfolder (the
//                     layout `aperture render` writes) reads images/
//   <file>.bag        RosbagSource (ROS1 bag; options.image_topic, options.imu_topic)
//   <file>            VideoFileSource (any container the installed OpenCV decodes)
//
// Throws std::invalid_argument for a malformed camera spec or a single image file given instead
// of its folder, std::runtime_error when the path does not exist; the sources' constructors throw
// for everything else (see their headers).
#include <memory>
#include <string>

#include "perception/io/frame_source.h"

namespace aperture::perception {

std::unique_ptr<FrameSource> OpenFrameSource(const std::string& spec,
                                             const FrameSourceOptions& options);

}  // namespace aperture::perception
