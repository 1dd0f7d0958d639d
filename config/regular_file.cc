#include "config/regular_file.h"

#include <filesystem>
#include <stdexcept>

namespace aperture::config {

void RequireRegularFileIfPresent(const std::string& path, const std::string& what) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) return;
  if (!std::filesystem::is_regular_file(status)) {
    throw std::invalid_argument(what + " '" + path +
                                "' is not a regular file (a device, FIFO, socket or folder); "
                                "give a file");
  }
}

}  // namespace aperture::config
