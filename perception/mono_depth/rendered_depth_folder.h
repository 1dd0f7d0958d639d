#pragma once
// A folder written by `aperture render` (images/*.png with depth/*.png of the same names, 16-bit
// mm) as training or evaluation data for monocular depth, and the ground-truth depth beside an
// image folder that `aperture run` plays.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace aperture::perception {

struct ImageDepthPair {
  std::filesystem::path image;
  std::filesystem::path depth;
};

// Every image of `folder`/images (natural order) with its `folder`/depth file. Throws
// std::invalid_argument naming the folder when either subfolder is missing, has no images, or an
// image has no depth of the same name.
std::vector<ImageDepthPair> ListRenderedDepthFrames(const std::filesystem::path& folder);

// The ground-truth depth folder beside an image source: `source`/depth when `source` holds an
// images/ folder (a render output), `source`/../depth when `source` is that images/ folder itself;
// nullopt when there is none (a camera, a video, plain images).
std::optional<std::filesystem::path> FindDepthBesideImages(const std::filesystem::path& source);

// The image files of a folder in the order ImageFolderSource plays them (natural order of names,
// .png only: the renderer's depth maps).
std::vector<std::filesystem::path> ListPngFiles(const std::filesystem::path& folder);

}  // namespace aperture::perception
