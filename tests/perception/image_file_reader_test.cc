#include "perception/io/image_file_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "tests/perception/temp_directory.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using ::testing::HasSubstr;

// A smooth non-constant image, so every format stores real pixel data (no trivially short file).
cv::Mat MakeTestImage(int channels) {
  cv::Mat image(48, 64, channels == 1 ? CV_8UC1 : CV_8UC3);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      if (channels == 1) {
        image.at<uchar>(r, c) = static_cast<uchar>(2 * r + c);
      } else {
        image.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<uchar>(2 * r), static_cast<uchar>(3 * c),
                                              static_cast<uchar>(r + c));
      }
    }
  }
  return image;
}

std::vector<unsigned char> Encode(const std::string& extension, int channels) {
  std::vector<unsigned char> bytes;
  EXPECT_TRUE(cv::imencode(extension, MakeTestImage(channels), bytes));
  return bytes;
}

// ReadImageFile's std::runtime_error message for `file` (empty and a test failure if it succeeds).
std::string MessageOfRead(const std::filesystem::path& file) {
  return test_support::MessageOf<std::runtime_error>(
      [&] { ReadImageFile(file, ColorMode::kGray); });
}

struct FormatCase {
  std::string extension;
  int channels;
};

void PrintTo(const FormatCase& format, std::ostream* os) {
  *os << format.extension << " with " << format.channels << " channel(s)";
}

class ImageFormat : public ::testing::TestWithParam<FormatCase> {};

TEST_P(ImageFormat, CompleteFileIsAcceptedAndEveryTruncationIsDetected) {
  const std::vector<unsigned char> bytes = Encode(GetParam().extension, GetParam().channels);
  EXPECT_FALSE(FindTruncation(bytes).has_value());
  // Cut anywhere from just after the 8-byte PNG signature to one byte short of complete.
  for (size_t keep : {size_t{10}, bytes.size() / 4, bytes.size() / 2, bytes.size() - 1}) {
    const std::vector<unsigned char> cut(bytes.begin(), bytes.begin() + keep);
    EXPECT_TRUE(FindTruncation(cut).has_value()) << "kept " << keep << " of " << bytes.size();
  }
}

TEST_P(ImageFormat, ReadImageFileRejectsTheFirstHalfOfARealFile) {
  test_support::TempDirectory dir;
  const std::filesystem::path file = dir.path() / ("half" + GetParam().extension);
  const std::vector<unsigned char> bytes = Encode(GetParam().extension, GetParam().channels);
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size() / 2));
  const std::string message = MessageOfRead(file);
  EXPECT_THAT(message, HasSubstr(file.string()));
  EXPECT_THAT(message, HasSubstr("truncated"));
}

INSTANTIATE_TEST_SUITE_P(StructurallyChecked, ImageFormat,
                         ::testing::Values(FormatCase{".png", 1}, FormatCase{".png", 3},
                                           FormatCase{".jpg", 3}, FormatCase{".pgm", 1},
                                           FormatCase{".ppm", 3}, FormatCase{".bmp", 3}),
                         [](const auto& info) {
                           return info.param.extension.substr(1) +
                                  std::to_string(info.param.channels);
                         });

TEST(ReadImageFile, ImreadAloneAcceptsATruncatedJpeg) {
  // Why the structural check exists: cv::imread returns a full-size image, with only a libjpeg
  // warning, for a JPEG cut in half (the missing rows are filled in). OpenCV 4.6 itself rejects
  // truncated PNGs (its decoder reads up to IEND); older versions did not, and the check gives a
  // precise message either way (BadFrame/TruncatedPng in frame_sources_test.cc).
  test_support::TempDirectory dir;
  const std::vector<unsigned char> jpeg = Encode(".jpg", 1);
  const std::filesystem::path file = dir.path() / "half.jpg";
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()),
             static_cast<std::streamsize>(jpeg.size() / 2));
  ::testing::internal::CaptureStderr();  // libjpeg's "Premature end of JPEG file"
  EXPECT_EQ(cv::imread(file.string(), cv::IMREAD_GRAYSCALE).size(), cv::Size(64, 48));
  ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(MessageOfRead(file), HasSubstr("truncated JPEG"));
}

TEST(ReadImageFile, DecodesLosslessFormatsExactlyInBothColorModes) {
  test_support::TempDirectory dir;
  const cv::Mat color = MakeTestImage(3);
  for (const std::string extension : {".png", ".ppm", ".bmp", ".tiff"}) {
    const std::filesystem::path file = dir.path() / ("image" + extension);
    ASSERT_TRUE(cv::imwrite(file.string(), color));
    const cv::Mat read_color = ReadImageFile(file, ColorMode::kColor);
    ASSERT_EQ(read_color.type(), CV_8UC3) << extension;
    EXPECT_EQ(cv::norm(read_color, color, cv::NORM_INF), 0.0) << extension;
    const cv::Mat read_gray = ReadImageFile(file, ColorMode::kGray);
    ASSERT_EQ(read_gray.type(), CV_8UC1) << extension;
    // Pixel (r, c) = BGR(2r, 3c, r + c): gray = 0.299 R + 0.587 G + 0.114 B, rounded (1 level).
    const int r = 20;
    const int c = 30;
    EXPECT_NEAR(read_gray.at<uchar>(r, c), 0.299 * (r + c) + 0.587 * (3 * c) + 0.114 * (2 * r), 1.0)
        << extension;
  }
}

TEST(DecodeImageBytes, DecodesContentAsReadImageFileDoesAndNamesTheGivenFile) {
  const std::vector<unsigned char> png = Encode(".png", 3);
  const cv::Mat decoded = DecodeImageBytes(png, "cam0/0001.png", ColorMode::kColor);
  EXPECT_EQ(cv::norm(decoded, MakeTestImage(3), cv::NORM_INF), 0.0);
  const std::vector<unsigned char> half(png.begin(), png.begin() + png.size() / 2);
  const std::string message = test_support::MessageOf<std::runtime_error>(
      [&] { DecodeImageBytes(half, "cam0/0001.png", ColorMode::kGray); });
  EXPECT_THAT(message, HasSubstr("'cam0/0001.png' is incomplete"));
}

TEST(ReadImageFile, GarbageEmptyAndMissingFilesNameTheFile) {
  test_support::TempDirectory dir;
  const std::filesystem::path garbage = dir.path() / "garbage.png";
  std::ofstream(garbage) << "this is not an image at all, just text with a .png name";
  // A TIFF signature, then nothing a TIFF decoder can read.
  const std::filesystem::path bad_tiff = dir.path() / "bad.tif";
  std::ofstream(bad_tiff) << "II*" << '\0' << "and then no image file directory at all";
  const std::filesystem::path empty = dir.path() / "empty.png";
  std::ofstream{empty};
  const std::filesystem::path missing = dir.path() / "missing.png";
  for (const auto& [file, expected] :
       {std::pair{garbage, "is not a PNG, JPEG, PNM, BMP or TIFF image"},
        std::pair{bad_tiff, "cannot be decoded"}, std::pair{empty, "is empty"},
        std::pair{missing, "cannot open"}}) {
    const std::string message = MessageOfRead(file);
    EXPECT_THAT(message, HasSubstr(file.string()));
    EXPECT_THAT(message, HasSubstr(expected));
  }
}

// Found by fuzz/image_file_fuzzer.cc: a DICOM file (128-byte preamble, "DICM") reached
// cv::imdecode, whose GDCM decoder aborted the process on this malformed one.
TEST(DecodeImageBytes, DicomContentIsRejectedBeforeDecoding) {
  std::string dicom = "6" + std::string(127, '\xff') + "DICM685";
  const std::vector<unsigned char> bytes(dicom.begin(), dicom.end());
  for (const ColorMode mode : {ColorMode::kGray, ColorMode::kColor}) {
    EXPECT_THAT(test_support::MessageOf<std::runtime_error>(
                    [&] { DecodeImageBytes(bytes, "seq/frame_3.png", mode); }),
                HasSubstr("'seq/frame_3.png' is not a PNG, JPEG, PNM, BMP or TIFF image"));
  }
}

// Found by fuzz/image_file_fuzzer.cc: 37 bytes of malformed ASCII PGM header made cv::imdecode
// allocate 3.1 GB.
TEST(DecodeImageBytes, MalformedAsciiPnmHeaderIsRejectedBeforeDecoding) {
  const std::string pgm = "P2\n588888x888P68\n68888888856\n6688T\n5#";
  const std::vector<unsigned char> bytes(pgm.begin(), pgm.end());
  EXPECT_THAT(test_support::MessageOf<std::runtime_error>(
                  [&] { DecodeImageBytes(bytes, "a.pgm", ColorMode::kColor); }),
              HasSubstr("'a.pgm' is incomplete: PNM header has no width and height"));
}

TEST(DecodeImageBytes, GigapixelHeadersAreRejectedBeforeDecoding) {
  // Headers of valid small images with their declared size patched to 60000 x 60000.
  std::vector<unsigned char> png = Encode(".png", 1);  // IHDR width, height at bytes 16, 20
  for (const size_t offset : {16, 20}) {
    png[offset] = 0;
    png[offset + 1] = 0;
    png[offset + 2] = 60000 >> 8;
    png[offset + 3] = 60000 & 0xFF;
  }
  const std::string pgm = "P2\n60000 60000\n255\n1 2 3\n";
  std::vector<unsigned char> jpeg = Encode(".jpg", 1);
  for (size_t i = 2; i + 8 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {  // SOF0: height, width at +5, +7
      for (const size_t offset : {i + 5, i + 7}) {
        jpeg[offset] = 60000 >> 8;
        jpeg[offset + 1] = 60000 & 0xFF;
      }
      break;
    }
  }
  for (const std::vector<unsigned char>& bytes :
       {png, std::vector<unsigned char>(pgm.begin(), pgm.end()), jpeg}) {
    EXPECT_THAT(test_support::MessageOf<std::runtime_error>(
                    [&] { DecodeImageBytes(bytes, "big", ColorMode::kGray); }),
                HasSubstr("'big' declares 60000 x 60000 pixels"));
  }
}

TEST(HasImageExtension, IsCaseInsensitiveAndRejectsOtherFiles) {
  EXPECT_TRUE(HasImageExtension("a/b/FRAME.PNG"));
  EXPECT_TRUE(HasImageExtension("x.tif"));
  EXPECT_TRUE(HasImageExtension("x.JpEg"));
  EXPECT_FALSE(HasImageExtension("times.txt"));
  EXPECT_FALSE(HasImageExtension("video.avi"));
  EXPECT_FALSE(HasImageExtension("png"));
}

}  // namespace
}  // namespace aperture::perception
