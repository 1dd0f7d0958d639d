// One image file of an image folder source (perception/io/image_file_reader.h): the completeness
// checks by content (PNG chunks, JPEG EOI, PNM payload, BMP size), OpenCV's decoding and the
// 8-bit check, in both colour modes.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "perception/io/image_file_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<unsigned char> bytes(data, data + size);
  for (const auto mode :
       {aperture::perception::ColorMode::kGray, aperture::perception::ColorMode::kColor}) {
    try {
      aperture::perception::DecodeImageBytes(bytes, "frame.png", mode);
    } catch (const std::runtime_error&) {
    }
  }
  return 0;
}
