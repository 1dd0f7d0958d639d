// An image folder's times.txt (perception/io/timestamps.h, both forms), then the ordering check
// the image folder source applies to it.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "perception/io/timestamps.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const aperture::perception::TimestampTable table =
        aperture::perception::ParseTimesTxt(in, "times.txt");
    std::vector<std::string> labels;
    for (const int line : table.line_numbers) labels.push_back("line " + std::to_string(line));
    aperture::perception::CheckStrictlyIncreasing(table.t_s, labels, "times.txt");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
