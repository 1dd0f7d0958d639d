// A EuRoC camera folder's data.csv (perception/io/timestamps.h), then the ordering check the image
// folder source applies to it, and the timestamps its file names encode.
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
        aperture::perception::ParseEurocDataCsv(in, "data.csv");
    for (const std::string& name : table.names) aperture::perception::TimestampFromFileName(name);
    aperture::perception::CheckStrictlyIncreasing(table.t_s, table.names, "data.csv");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
