#pragma once
// Reading one image file of a sequence completely or not at all.
//
// cv::imread accepts a truncated PNG or JPEG and returns a partly decoded image (the missing rows
// are gray or garbage) with at most a libpng/libjpeg warning on stderr. A frame source must not
// feed that to a front end, so files are checked for completeness from their own structure before
// decoding (by content, not by extension):
//   PNG         every chunk length fits in the file and the chunk sequence reaches IEND;
//   JPEG        the data ends with the EOI marker FF D9 (trailing zero padding allowed);
//   PGM/PPM     (binary P5/P6) the pixel payload width*height*channels*bytes is all present;
//   BMP         the file is at least as long as the size in its header.
//   PNM         (ASCII P1-P3, binary PBM P4) the header holds a width and a height.
// Other formats (TIFF) and the pixels of ASCII PNM rely on the decoder's own checks. Content of any
// other format (DICOM, JPEG 2000, WebP, ..., which cv::imdecode would try) is rejected before
// decoding.
#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "perception/io/frame_source.h"

namespace aperture::perception {

// Largest frame ReadImageFile decodes (8192 x 8192): a header declaring more is rejected before
// decoding allocates it (checked for PNG, BMP, PNM and JPEG; TIFF relies on OpenCV's 2^30).
inline constexpr uint64_t kMaxImagePixels = uint64_t{1} << 26;

// Why the encoded image `bytes` are incomplete, or nullopt when complete (or of a format
// without a structural check).
std::optional<std::string> FindTruncation(const std::vector<unsigned char>& bytes);

// Reads, checks and decodes `path` into an 8-bit image of the given colour mode. Throws
// std::runtime_error naming the file when it cannot be read (a dangling symbolic link names its
// target), is not a PNG, JPEG, PNM, BMP or TIFF image, is truncated, declares more than
// kMaxImagePixels, cannot be decoded, or has 16-bit (or float) samples.
cv::Mat ReadImageFile(const std::filesystem::path& path, ColorMode mode);

// ReadImageFile's checks and decoding of a file's content `bytes`; `name` (the file) names it in
// the std::runtime_error.
cv::Mat DecodeImageBytes(const std::vector<unsigned char>& bytes, const std::string& name,
                         ColorMode mode);

// True when the extension (case-insensitive) is one the image folder source reads:
// .png .jpg .jpeg .pgm .ppm .pnm .bmp .tif .tiff
bool HasImageExtension(const std::filesystem::path& path);

}  // namespace aperture::perception
