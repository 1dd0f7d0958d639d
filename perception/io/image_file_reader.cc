#include "perception/io/image_file_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

using Bytes = std::vector<unsigned char>;

uint32_t ReadBigEndian32(const Bytes& bytes, size_t offset) {
  return (uint32_t{bytes[offset]} << 24) | (uint32_t{bytes[offset + 1]} << 16) |
         (uint32_t{bytes[offset + 2]} << 8) | uint32_t{bytes[offset + 3]};
}

uint32_t ReadLittleEndian32(const Bytes& bytes, size_t offset) {
  return uint32_t{bytes[offset]} | (uint32_t{bytes[offset + 1]} << 8) |
         (uint32_t{bytes[offset + 2]} << 16) | (uint32_t{bytes[offset + 3]} << 24);
}

bool StartsWith(const Bytes& bytes, std::initializer_list<unsigned char> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

// PNG: 8-byte signature, then chunks of {length (4, big endian), type (4), data, CRC (4)}.
std::optional<std::string> FindPngTruncation(const Bytes& bytes) {
  constexpr size_t kSignatureSize = 8;
  constexpr size_t kChunkOverhead = 12;
  size_t offset = kSignatureSize;
  while (offset + kChunkOverhead <= bytes.size()) {
    const uint64_t length = ReadBigEndian32(bytes, offset);
    const std::string type(bytes.begin() + offset + 4, bytes.begin() + offset + 8);
    const uint64_t chunk_end = offset + kChunkOverhead + length;
    if (chunk_end > bytes.size()) {
      return "PNG chunk '" + type + "' at byte " + std::to_string(offset) + " needs " +
             std::to_string(chunk_end) + " bytes but the file has " + std::to_string(bytes.size()) +
             " (truncated PNG)";
    }
    if (type == "IEND") return std::nullopt;
    offset = chunk_end;
  }
  return "PNG ends after " + std::to_string(bytes.size()) +
         " bytes without its IEND chunk (truncated PNG)";
}

std::optional<std::string> FindJpegTruncation(const Bytes& bytes) {
  size_t end = bytes.size();
  while (end > 2 && bytes[end - 1] == 0) --end;
  if (end >= 4 && bytes[end - 2] == 0xFF && bytes[end - 1] == 0xD9) return std::nullopt;
  return "JPEG ends after " + std::to_string(bytes.size()) +
         " bytes without its end-of-image marker FF D9 (truncated JPEG)";
}

// The first `fields.size()` numbers of a PNM header "P<n> <width> <height> [<maxval>]" (comments
// from '#' to the end of a line allowed between them): the offset just after the last one, or
// nullopt when the header ends before them.
template <size_t N>
std::optional<size_t> ReadPnmHeader(const Bytes& bytes, std::array<uint64_t, N>* fields) {
  size_t offset = 2;
  for (uint64_t& field : *fields) {
    field = 0;
    while (offset < bytes.size() && (std::isspace(bytes[offset]) || bytes[offset] == '#')) {
      if (bytes[offset] == '#') {
        while (offset < bytes.size() && bytes[offset] != '\n') ++offset;
      } else {
        ++offset;
      }
    }
    if (offset >= bytes.size() || !std::isdigit(bytes[offset])) return std::nullopt;
    while (offset < bytes.size() && std::isdigit(bytes[offset]) && field < (1u << 30)) {
      field = field * 10 + (bytes[offset] - '0');
      ++offset;
    }
  }
  return offset;
}

// Binary PGM (P5) / PPM (P6): "P5 <width> <height> <maxval>" + one whitespace, then the pixels.
std::optional<std::string> FindPnmTruncation(const Bytes& bytes) {
  std::array<uint64_t, 3> fields{};  // width, height, maxval
  const std::optional<size_t> header_end = ReadPnmHeader(bytes, &fields);
  if (!header_end) return std::string("PGM/PPM header is incomplete (truncated or corrupt)");
  const uint64_t offset = *header_end + 1;  // the single whitespace after maxval
  const uint64_t channels = bytes[1] == '5' ? 1 : 3;
  const uint64_t bytes_per_sample = fields[2] > 255 ? 2 : 1;
  const uint64_t needed = offset + fields[0] * fields[1] * channels * bytes_per_sample;
  if (needed > bytes.size()) {
    return "PGM/PPM pixel data needs " + std::to_string(needed) + " bytes but the file has " +
           std::to_string(bytes.size()) + " (truncated image)";
  }
  return std::nullopt;
}

std::optional<std::string> FindBmpTruncation(const Bytes& bytes) {
  constexpr size_t kFileHeaderSize = 14;
  if (bytes.size() < kFileHeaderSize) return std::string("BMP header is incomplete (truncated)");
  const uint32_t declared_size = ReadLittleEndian32(bytes, 2);
  if (declared_size > bytes.size()) {
    return "BMP header declares " + std::to_string(declared_size) + " bytes but the file has " +
           std::to_string(bytes.size()) + " (truncated BMP)";
  }
  return std::nullopt;
}

// The formats of HasImageExtension, by their signatures. cv::imdecode also decodes DICOM,
// JPEG 2000, OpenEXR, Radiance HDR, WebP, Sun raster and more, whatever the file name; their
// decoders are not for input we do not expect (GDCM aborts the process on a malformed DICOM file).
uint32_t ReadBigEndian16(const Bytes& bytes, size_t offset) {
  return (uint32_t{bytes[offset]} << 8) | uint32_t{bytes[offset + 1]};
}

struct DeclaredSize {
  uint64_t width = 0;
  uint64_t height = 0;
};

// The image size a PNG (IHDR), BMP (info header), PNM or JPEG (start-of-frame marker) header
// declares, read before decoding: a few bytes can declare a gigapixel image, which cv::imdecode
// would allocate (up to its own limit of 2^30 pixels) before finding the data missing. nullopt
// for TIFF and for a header too short to tell (the decoder then rejects the file).
std::optional<DeclaredSize> FindDeclaredSize(const Bytes& bytes) {
  if (StartsWith(bytes, {0x89, 'P', 'N', 'G'}) && bytes.size() >= 24) {
    return DeclaredSize{ReadBigEndian32(bytes, 16), ReadBigEndian32(bytes, 20)};
  }
  if (StartsWith(bytes, {'B', 'M'}) && bytes.size() >= 26) {
    if (ReadLittleEndian32(bytes, 14) == 12) {  // OS/2 BITMAPCOREHEADER: 16-bit sizes
      return DeclaredSize{bytes[18] | (uint64_t{bytes[19]} << 8),
                          bytes[20] | (uint64_t{bytes[21]} << 8)};
    }
    const auto width = static_cast<int32_t>(ReadLittleEndian32(bytes, 18));
    const auto height = static_cast<int32_t>(ReadLittleEndian32(bytes, 22));  // < 0: top-down
    return DeclaredSize{static_cast<uint64_t>(std::abs(int64_t{width})),
                        static_cast<uint64_t>(std::abs(int64_t{height}))};
  }
  if (bytes.size() >= 2 && bytes[0] == 'P') {
    std::array<uint64_t, 2> fields{};
    if (!ReadPnmHeader(bytes, &fields)) return std::nullopt;
    return DeclaredSize{fields[0], fields[1]};
  }
  if (StartsWith(bytes, {0xFF, 0xD8})) {
    size_t offset = 2;
    while (offset + 9 <= bytes.size() && bytes[offset] == 0xFF) {
      const unsigned char marker = bytes[offset + 1];
      if (marker == 0xFF) {  // fill byte
        ++offset;
      } else if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {  // no length
        offset += 2;
      } else if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                 marker != 0xCC) {  // SOFn: length, precision, height, width
        return DeclaredSize{ReadBigEndian16(bytes, offset + 7), ReadBigEndian16(bytes, offset + 5)};
      } else if (marker == 0xDA || marker == 0xD9) {  // scan data or end before any frame
        return std::nullopt;
      } else {
        offset += 2 + ReadBigEndian16(bytes, offset + 2);
      }
    }
  }
  return std::nullopt;
}

bool HasFrameSourceFormat(const Bytes& bytes) {
  const bool pnm = bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6';
  return pnm || StartsWith(bytes, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}) ||
         StartsWith(bytes, {0xFF, 0xD8, 0xFF}) || StartsWith(bytes, {'B', 'M'}) ||
         StartsWith(bytes, {'I', 'I', 42, 0}) || StartsWith(bytes, {'M', 'M', 0, 42});
}

}  // namespace

std::optional<std::string> FindTruncation(const Bytes& bytes) {
  if (StartsWith(bytes, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'})) {
    return FindPngTruncation(bytes);
  }
  if (StartsWith(bytes, {0xFF, 0xD8})) return FindJpegTruncation(bytes);
  if (StartsWith(bytes, {'P', '5'}) || StartsWith(bytes, {'P', '6'})) {
    return FindPnmTruncation(bytes);
  }
  if (std::array<uint64_t, 2> size{}; bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' &&
                                      bytes[1] <= '4' && !ReadPnmHeader(bytes, &size)) {
    // ASCII PBM/PGM/PPM and binary PBM: the pixels are not checked, the header is (OpenCV's
    // reader makes sizes of a malformed one).
    return std::string("PNM header has no width and height (truncated or corrupt)");
  }
  if (StartsWith(bytes, {'B', 'M'})) return FindBmpTruncation(bytes);
  return std::nullopt;
}

cv::Mat ReadImageFile(const std::filesystem::path& path, ColorMode mode) {
  std::error_code error;
  if (std::filesystem::is_symlink(path, error) && !std::filesystem::exists(path, error)) {
    throw std::runtime_error("image file '" + path.string() + "' is a symbolic link to '" +
                             std::filesystem::read_symlink(path, error).string() +
                             "', which does not exist; restore the target or remove the link");
  }
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) {
    throw std::runtime_error("cannot open image file '" + path.string() +
                             "'; check that it exists and is readable");
  }
  Bytes bytes(static_cast<size_t>(file.tellg()));
  file.seekg(0);
  if (!file.read(reinterpret_cast<char*>(bytes.data()),
                 static_cast<std::streamsize>(bytes.size()))) {
    throw std::runtime_error("cannot read image file '" + path.string() +
                             "'; check that it is a readable regular file");
  }
  return DecodeImageBytes(bytes, path.string(), mode);
}

cv::Mat DecodeImageBytes(const std::vector<unsigned char>& bytes, const std::string& name,
                         ColorMode mode) {
  if (bytes.empty()) {
    throw std::runtime_error("image file '" + name +
                             "' is empty; re-export it or remove it from the sequence");
  }
  if (!HasFrameSourceFormat(bytes)) {
    throw std::runtime_error("image file '" + name +
                             "' is not a PNG, JPEG, PNM, BMP or TIFF image (frame sources read "
                             "only those); convert it or remove it from the sequence");
  }
  if (const std::optional<std::string> truncation = FindTruncation(bytes)) {
    throw std::runtime_error("image file '" + name + "' is incomplete: " + *truncation +
                             "; re-copy or re-export it");
  }
  if (const std::optional<DeclaredSize> size = FindDeclaredSize(bytes);
      size && size->width * size->height > kMaxImagePixels) {
    throw std::runtime_error("image file '" + name + "' declares " + std::to_string(size->width) +
                             " x " + std::to_string(size->height) + " pixels, more than the " +
                             std::to_string(kMaxImagePixels) +
                             " a frame may have (8192 x 8192); corrupt or not a camera frame");
  }
  // IMREAD_ANYDEPTH: a 16-bit image comes back as such instead of silently losing its low byte.
  const int flags =
      (mode == ColorMode::kGray ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR) | cv::IMREAD_ANYDEPTH;
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("image file '" + name + "' cannot be decoded (" + e.what() +
                             "); re-export it");
  }
  if (image.empty()) {
    throw std::runtime_error("image file '" + name +
                             "' cannot be decoded (corrupt or not an image); re-export it");
  }
  if (image.depth() != CV_8U) {
    throw std::runtime_error(
        "image file '" + name + "' has " + std::to_string(8 * image.elemSize1()) +
        "-bit samples; frame sources take 8-bit images, and cutting to the high byte would hide "
        "e.g. 12-bit data: convert the sequence to 8 bits over its actual range");
  }
  return ConvertToColorMode(image, mode);
}

bool HasImageExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::array<const char*, 9> kExtensions = {".png", ".jpg", ".jpeg", ".pgm", ".ppm",
                                                         ".pnm", ".bmp", ".tif",  ".tiff"};
  return std::find(kExtensions.begin(), kExtensions.end(), extension) != kExtensions.end();
}

}  // namespace aperture::perception
