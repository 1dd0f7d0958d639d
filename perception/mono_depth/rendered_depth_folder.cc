#include "perception/mono_depth/rendered_depth_folder.h"

#include <stdexcept>

#include "perception/io/natural_sort.h"

namespace aperture::perception {

std::vector<std::filesystem::path> ListPngFiles(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name[0] != '.' && entry.path().extension() == ".png") {
      names.push_back(name);
    }
  }
  NaturalSort(names);
  std::vector<std::filesystem::path> files;
  for (const std::string& name : names) files.push_back(folder / name);
  return files;
}

std::vector<ImageDepthPair> ListRenderedDepthFrames(const std::filesystem::path& folder) {
  const std::filesystem::path images = folder / "images", depth = folder / "depth";
  if (!std::filesystem::is_directory(images) || !std::filesystem::is_directory(depth)) {
    throw std::invalid_argument("'" + folder.string() +
                                "' has no images/ and depth/ folders; give a folder written by "
                                "`aperture render forest --set cameras.front.color=true`");
  }
  std::vector<ImageDepthPair> pairs;
  for (const std::filesystem::path& image : ListPngFiles(images)) {
    const std::filesystem::path depth_file = depth / image.filename();
    if (!std::filesystem::is_regular_file(depth_file)) {
      throw std::invalid_argument("'" + image.string() + "' has no depth '" + depth_file.string() +
                                  "'; re-render the folder");
    }
    pairs.push_back({image, depth_file});
  }
  if (pairs.empty()) {
    throw std::invalid_argument("'" + images.string() + "' holds no .png images");
  }
  return pairs;
}

std::optional<std::filesystem::path> FindDepthBesideImages(const std::filesystem::path& source) {
  std::error_code error;
  if (!std::filesystem::is_directory(source, error)) return std::nullopt;
  if (std::filesystem::is_directory(source / "images", error) &&
      std::filesystem::is_directory(source / "depth", error)) {
    return source / "depth";
  }
  std::filesystem::path images = std::filesystem::absolute(source).lexically_normal();
  if (images.filename().empty()) images = images.parent_path();  // "images/"
  const std::filesystem::path parent = images.parent_path();
  if (images.filename() == "images" && std::filesystem::is_directory(parent / "depth", error)) {
    return parent / "depth";
  }
  return std::nullopt;
}

}  // namespace aperture::perception
