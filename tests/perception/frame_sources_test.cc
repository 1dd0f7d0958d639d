// Frame sources against generated sequences: every timestamp source, both colour modes, and each
// kind of bad input in strict mode (throws, naming the file and the fix) and in skip mode
// (frame skipped, recorded and warned about, the rest delivered).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "perception/io/image_folder_source.h"
#include "perception/io/in_process_source.h"
#include "perception/io/open_frame_source.h"
#include "perception/io/video_file_source.h"
#include "tests/perception/temp_directory.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using test_support::MessageOf;

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const cv::Size kSize(40, 30);

// Frame k of a test sequence: uniform gray level 10 * k + 5, so its content identifies it.
cv::Mat GrayFrame(int k, cv::Size size = kSize) {
  return cv::Mat(size, CV_8UC1, cv::Scalar(10 * k + 5));
}

int LevelOf(const Frame& frame) { return static_cast<int>(cv::mean(frame.image)[0] + 0.5); }

void WriteImage(const fs::path& file, const cv::Mat& image) {
  ASSERT_TRUE(cv::imwrite(file.string(), image)) << file;
}

void WriteText(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

// Keeps the first half of `file`, as an interrupted copy would.
void TruncateToHalf(const fs::path& file) { fs::resize_file(file, fs::file_size(file) / 2); }

std::vector<Frame> ReadAll(FrameSource& source) {
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = source.Next()) frames.push_back(std::move(*frame));
  return frames;
}

FrameSourceOptions SourceOptions(double fps, bool skip = false, ColorMode mode = ColorMode::kGray) {
  FrameSourceOptions options;
  options.fps = fps;
  options.skip_bad_frames = skip;
  options.color_mode = mode;
  return options;
}

// Writes frame1.png .. frame<n>.png (natural order differs from lexical order for n >= 10).
void WriteSequence(const fs::path& folder, int n) {
  for (int k = 1; k <= n; ++k)
    WriteImage(folder / ("frame" + std::to_string(k) + ".png"), GrayFrame(k));
}

// ---------------------------------------------------------------- image folders: good input

TEST(ImageFolderSource, PlaysInNaturalOrderTimedByFps) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 12);
  ImageFolderSource source(dir.path(), SourceOptions(20.0));
  EXPECT_EQ(source.SizeHint(), std::optional<size_t>(12));
  EXPECT_EQ(source.TimeSource(), "fps");
  const std::vector<Frame> frames = ReadAll(source);
  ASSERT_EQ(frames.size(), 12u);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(frames[i].index, i);
    EXPECT_DOUBLE_EQ(frames[i].t_s, i / 20.0);
    EXPECT_EQ(LevelOf(frames[i]), 10 * (i + 1) + 5) << "frame" << i + 1 << " out of order";
    EXPECT_EQ(frames[i].image.type(), CV_8UC1);
  }
  EXPECT_TRUE(source.SkippedFrames().empty());
  EXPECT_FALSE(source.Next().has_value());  // stays at the end
}

TEST(ImageFolderSource, ColorModeGivesBgrOrGrayFromEveryFormat) {
  test_support::TempDirectory dir;
  // B, G, R distinct so a channel swap shows; gray = 0.299 R + 0.587 G + 0.114 B = 119.64.
  const cv::Mat color(kSize, CV_8UC3, cv::Scalar(10, 100, 200));
  const std::vector<std::string> extensions = {".png", ".jpg", ".ppm", ".bmp", ".tiff"};
  for (size_t k = 0; k < extensions.size(); ++k) {
    WriteImage(dir.path() / ("f" + std::to_string(k) + extensions[k]), color);
  }
  WriteImage(dir.path() / ("f" + std::to_string(extensions.size()) + ".pgm"), GrayFrame(3));

  ImageFolderSource color_source(dir.path(), SourceOptions(10.0, false, ColorMode::kColor));
  const std::vector<Frame> color_frames = ReadAll(color_source);
  ASSERT_EQ(color_frames.size(), extensions.size() + 1);
  for (size_t k = 0; k < extensions.size(); ++k) {
    ASSERT_EQ(color_frames[k].image.type(), CV_8UC3) << extensions[k];
    const cv::Scalar mean = cv::mean(color_frames[k].image);
    // JPEG of a uniform image is within 2 levels per channel; lossless formats are exact.
    EXPECT_NEAR(mean[0], 10, 2) << extensions[k];
    EXPECT_NEAR(mean[1], 100, 2) << extensions[k];
    EXPECT_NEAR(mean[2], 200, 2) << extensions[k];
  }
  // A gray file in colour mode becomes three equal channels.
  const cv::Scalar pgm_mean = cv::mean(color_frames.back().image);
  EXPECT_EQ(color_frames.back().image.type(), CV_8UC3);
  EXPECT_DOUBLE_EQ(pgm_mean[0], 35);
  EXPECT_DOUBLE_EQ(pgm_mean[2], 35);

  ImageFolderSource gray_source(dir.path(), SourceOptions(10.0, false, ColorMode::kGray));
  const std::vector<Frame> gray_frames = ReadAll(gray_source);
  ASSERT_EQ(gray_frames.size(), extensions.size() + 1);
  for (size_t k = 0; k < extensions.size(); ++k) {
    ASSERT_EQ(gray_frames[k].image.type(), CV_8UC1) << extensions[k];
    EXPECT_NEAR(cv::mean(gray_frames[k].image)[0], 119.64, 2) << extensions[k];
  }
}

TEST(ImageFolderSource, TimesTxtSingleColumnIsPositional) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "# seconds\n1.5\n1.6\n1.75\n");
  ImageFolderSource source(dir.path(), SourceOptions(99.0));  // times.txt wins over fps
  EXPECT_EQ(source.TimeSource(), "times.txt");
  const std::vector<Frame> frames = ReadAll(source);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(frames[0].t_s, 1.5);
  EXPECT_DOUBLE_EQ(frames[1].t_s, 1.6);
  EXPECT_DOUBLE_EQ(frames[2].t_s, 1.75);
}

TEST(ImageFolderSource, TimesTxtPairsMatchByNameInAnyLineOrder) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "frame3.png 0.3\nframe1 0.1\n0.2 frame2.png\n");
  ImageFolderSource source(dir.path(), SourceOptions(0.0));
  const std::vector<Frame> frames = ReadAll(source);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(frames[i].t_s, 0.1 * (i + 1));
    EXPECT_EQ(LevelOf(frames[i]), 10 * (i + 1) + 5);
  }
}

// EuRoC layout: cam0/data.csv and cam0/data/<ns>.png; the csv names differ from the time so the
// test shows the time comes from the csv, not from the file names.
fs::path WriteEurocCamera(const fs::path& root, const std::string& extra_csv_line = "") {
  const fs::path cam0 = root / "cam0";
  fs::create_directories(cam0 / "data");
  std::string csv = "#timestamp [ns],filename\n";
  for (int k = 0; k < 3; ++k) {
    const long long t_ns = 1403636579763555584LL + k * 50000000LL;
    const std::string name = "img" + std::to_string(k) + ".png";
    WriteImage(cam0 / "data" / name, GrayFrame(k));
    csv += std::to_string(t_ns) + "," + name + "\n";
  }
  WriteText(cam0 / "data.csv", csv + extra_csv_line);
  return cam0;
}

TEST(ImageFolderSource, EurocDataCsvFromCameraFolderOrItsDataFolder) {
  test_support::TempDirectory dir;
  const fs::path cam0 = WriteEurocCamera(dir.path());
  // With a trailing separator too: the parent of "cam0/data/" must still be cam0.
  for (const fs::path& spec : {cam0, cam0 / "data", cam0 / "data" / ""}) {
    ImageFolderSource source(spec, SourceOptions(0.0));
    EXPECT_EQ(source.TimeSource(), "data.csv") << spec;
    const std::vector<Frame> frames = ReadAll(source);
    ASSERT_EQ(frames.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      // double resolution at 1.4e9 s is 2.4e-7 s.
      EXPECT_NEAR(frames[k].t_s, 1403636579.763555584 + 0.05 * k, 5e-7);
    }
  }
}

TEST(ImageFolderSource, NanosecondFileNamesAreTimesSmallNumbersNeedFps) {
  test_support::TempDirectory dir;
  const fs::path ns = dir.path() / "ns";
  const fs::path counters = dir.path() / "counters";
  fs::create_directories(ns);
  fs::create_directories(counters);
  WriteImage(ns / "1403636579763555584.png", GrayFrame(0));
  WriteImage(ns / "1403636579813555456.png", GrayFrame(1));
  WriteImage(counters / "000001.png", GrayFrame(0));
  WriteImage(counters / "000002.png", GrayFrame(1));

  ImageFolderSource from_names(ns, SourceOptions(0.0));
  EXPECT_EQ(from_names.TimeSource(), "file names");
  EXPECT_NEAR(from_names.Times()[1] - from_names.Times()[0], 0.049999872, 5e-7);

  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(counters, SourceOptions(0.0)); });
  EXPECT_THAT(message, HasSubstr(counters.string()));
  EXPECT_THAT(message, HasSubstr("--fps"));
  EXPECT_THAT(message, HasSubstr("times.txt"));
  ImageFolderSource with_fps(counters, SourceOptions(30.0));
  EXPECT_EQ(with_fps.TimeSource(), "fps");
  EXPECT_DOUBLE_EQ(with_fps.Times()[1], 1.0 / 30.0);
}

// ---------------------------------------------------------------- image folders: bad input

// Whole-sequence errors throw in both modes.
class BothModes : public ::testing::TestWithParam<bool> {
 protected:
  FrameSourceOptions options(double fps = 10.0) const { return SourceOptions(fps, GetParam()); }
};

TEST_P(BothModes, MissingFolderNamesIt) {
  test_support::TempDirectory dir;
  const fs::path missing = dir.path() / "no_such_sequence";
  const std::string message =
      MessageOf<std::runtime_error>([&] { ImageFolderSource(missing, options()); });
  EXPECT_THAT(message, HasSubstr(missing.string()));
  EXPECT_THAT(message, HasSubstr("does not exist"));
}

TEST_P(BothModes, FolderWithoutImagesNamesItAndTheExtensions) {
  test_support::TempDirectory dir;
  WriteText(dir.path() / "notes.txt", "no images here\n");
  fs::create_directories(dir.path() / "sub");
  WriteImage(dir.path() / "sub" / "frame1.png", GrayFrame(1));  // subfolders are not searched
  const std::string message =
      MessageOf<std::runtime_error>([&] { ImageFolderSource(dir.path(), options()); });
  EXPECT_THAT(message, HasSubstr(dir.path().string()));
  EXPECT_THAT(message, HasSubstr("contains no images"));
  EXPECT_THAT(message, HasSubstr(".png"));
}

TEST_P(BothModes, TimesTxtWithWrongLineCountGivesBothCounts) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "0.0\n0.1\n");
  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(dir.path(), options()); });
  EXPECT_THAT(message, HasSubstr((dir.path() / "times.txt").string()));
  EXPECT_THAT(message, HasSubstr("has 2 timestamps but the folder has 3 images"));
}

TEST_P(BothModes, NonMonotonicTimesNameBothFiles) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "0.0\n0.2\n0.1\n");
  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(dir.path(), options()); });
  EXPECT_THAT(message, HasSubstr("'frame3.png'"));
  EXPECT_THAT(message, HasSubstr("is before that of 'frame2.png'"));
  EXPECT_THAT(message, HasSubstr("times.txt"));
}

TEST_P(BothModes, DuplicateTimesAreRejected) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "frame1.png 0.0\nframe2.png 0.1\nframe3.png 0.1\n");
  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(dir.path(), options()); });
  EXPECT_THAT(message, HasSubstr("'frame3.png'"));
  EXPECT_THAT(message, HasSubstr("duplicates that of 'frame2.png'"));
}

TEST_P(BothModes, UnparsableDataCsvLineNamesFileAndLine) {
  test_support::TempDirectory dir;
  const fs::path cam0 = WriteEurocCamera(dir.path(), "14036365798x3555584,img3.png\n");
  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(cam0, options()); });
  EXPECT_THAT(message, HasSubstr((cam0 / "data.csv").string() + " line 5"));
  EXPECT_THAT(message, HasSubstr("'14036365798x3555584'"));
}

TEST_P(BothModes, NegativeFpsIsRejected) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 2);
  EXPECT_THAT(MessageOf<std::invalid_argument>([&] { ImageFolderSource(dir.path(), options(-5)); }),
              HasSubstr("fps = -5"));
}

INSTANTIATE_TEST_SUITE_P(ImageFolderSource, BothModes, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "skip" : "strict"; });

// Bad frames: strict mode throws at the bad frame after delivering the good ones before it; skip
// mode delivers all good frames, records the bad one and warns on stderr.
struct BadFrameCase {
  std::string name;
  std::function<void(const fs::path& file)> spoil;  // turns the good file frame3.png bad
  std::string strict_exception;                     // "runtime_error" or "invalid_argument"
  std::string reason;                               // expected in message and skip reason
};

void PrintTo(const BadFrameCase& bad_frame, std::ostream* os) { *os << bad_frame.name; }

class BadFrame : public ::testing::TestWithParam<BadFrameCase> {};

TEST_P(BadFrame, StrictModeThrowsNamingTheFile) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 5);
  const fs::path bad = dir.path() / "frame3.png";
  GetParam().spoil(bad);
  ImageFolderSource source(dir.path(), SourceOptions(10.0, false));
  ASSERT_TRUE(source.Next().has_value());
  ASSERT_TRUE(source.Next().has_value());
  std::string message;
  if (GetParam().strict_exception == "runtime_error") {
    message = MessageOf<std::runtime_error>([&] { source.Next(); });
  } else {
    message = MessageOf<std::invalid_argument>([&] { source.Next(); });
  }
  EXPECT_THAT(message, HasSubstr(bad.string()));
  EXPECT_THAT(message, HasSubstr(GetParam().reason));
  EXPECT_THAT(message, HasSubstr("--skip-bad-frames"));
}

TEST_P(BadFrame, SkipModeRecordsAndWarns) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 5);
  const fs::path bad = dir.path() / "frame3.png";
  GetParam().spoil(bad);
  ImageFolderSource source(dir.path(), SourceOptions(10.0, true));
  ::testing::internal::CaptureStderr();
  const std::vector<Frame> frames = ReadAll(source);
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(frames.size(), 4u);
  // Good frames keep their positions and times; the gap shows where frame3 was.
  const std::vector<int> expected_index = {0, 1, 3, 4};
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, expected_index[i]);
    EXPECT_DOUBLE_EQ(frames[i].t_s, expected_index[i] / 10.0);
    EXPECT_EQ(LevelOf(frames[i]), 10 * (expected_index[i] + 1) + 5);
  }
  ASSERT_EQ(source.SkippedFrames().size(), 1u);
  EXPECT_EQ(source.SkippedFrames()[0].item, bad.string());
  EXPECT_THAT(source.SkippedFrames()[0].reason, HasSubstr(GetParam().reason));
  EXPECT_THAT(stderr_text, HasSubstr("warning: "));
  EXPECT_THAT(stderr_text, HasSubstr("skipping " + bad.string()));
}

INSTANTIATE_TEST_SUITE_P(
    ImageFolderSource, BadFrame,
    ::testing::Values(
        BadFrameCase{"CorruptBytes",
                     [](const fs::path& file) {
                       WriteText(file, "garbage bytes pretending to be a PNG file\x01\x02\x03");
                     },
                     "runtime_error", "is not a PNG, JPEG, PNM, BMP or TIFF image"},
        BadFrameCase{"TruncatedPng", TruncateToHalf, "runtime_error", "truncated PNG"},
        BadFrameCase{"TruncatedJpegWithPngName",
                     [](const fs::path& file) {
                       std::vector<unsigned char> jpeg;
                       cv::imencode(".jpg", GrayFrame(3), jpeg);
                       jpeg.resize(jpeg.size() / 2);
                       std::ofstream(file, std::ios::binary)
                           .write(reinterpret_cast<const char*>(jpeg.data()),
                                  static_cast<std::streamsize>(jpeg.size()));
                     },
                     "runtime_error", "truncated JPEG"},
        BadFrameCase{"WrongSize",
                     [](const fs::path& file) { WriteImage(file, GrayFrame(3, cv::Size(41, 30))); },
                     "invalid_argument", "is 41x30 but the sequence started 40x30"}),
    [](const auto& info) { return info.param.name; });

TEST(ImageFolderSource, ListedButMissingFilesAndUntimedImagesThrowOrAreRecorded) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  WriteText(dir.path() / "times.txt", "frame1.png 0.1\nframe2.png 0.2\nframe9.png 0.9\n");
  // frame3.png has no line; frame9.png has a line but no file.
  const std::string message =
      MessageOf<std::invalid_argument>([&] { ImageFolderSource(dir.path(), SourceOptions(0.0)); });
  EXPECT_THAT(message, HasSubstr((dir.path() / "frame3.png").string()));
  EXPECT_THAT(message, HasSubstr("has no timestamp"));

  ::testing::internal::CaptureStderr();
  ImageFolderSource source(dir.path(), SourceOptions(0.0, true));
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(ReadAll(source).size(), 2u);
  ASSERT_EQ(source.SkippedFrames().size(), 2u);
  EXPECT_EQ(source.SkippedFrames()[0].item, (dir.path() / "frame3.png").string());
  EXPECT_EQ(source.SkippedFrames()[1].item, (dir.path() / "frame9.png").string());
  EXPECT_THAT(source.SkippedFrames()[1].reason, HasSubstr("line 3"));
  EXPECT_THAT(stderr_text, HasSubstr("frame9.png"));
}

TEST(ImageFolderSource, AllFramesBadInSkipModeEndsWithEveryOneRecorded) {
  test_support::TempDirectory dir;
  WriteText(dir.path() / "a.png", "not a png");
  WriteText(dir.path() / "b.png", "not a png either");
  ImageFolderSource source(dir.path(), SourceOptions(10.0, true));
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(source.Next().has_value());
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(source.SkippedFrames().size(), 2u);
}

// ---------------------------------------------------------------- video files

// Writes n frames of GrayFrame(k) as MJPG in an .avi at `fps`.
void WriteVideo(const fs::path& file, int n, double fps) {
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, kSize,
                         /*isColor=*/true);
  ASSERT_TRUE(writer.isOpened()) << "OpenCV cannot write MJPG .avi";
  cv::Mat bgr;
  for (int k = 0; k < n; ++k) {
    cv::cvtColor(GrayFrame(k), bgr, cv::COLOR_GRAY2BGR);
    writer.write(bgr);
  }
}

TEST(VideoFileSource, ReadsBackEveryFrameInOrderWithContainerTimes) {
  test_support::TempDirectory dir;
  const fs::path video = dir.path() / "clip.avi";
  WriteVideo(video, 7, 10.0);
  VideoFileSource source(video, SourceOptions(0.0, false, ColorMode::kGray));
  EXPECT_EQ(source.SizeHint(), std::optional<size_t>(7));
  const std::vector<Frame> frames = ReadAll(source);
  ASSERT_EQ(frames.size(), 7u);
  for (int k = 0; k < 7; ++k) {
    EXPECT_EQ(frames[k].index, k);
    EXPECT_NEAR(frames[k].t_s, k / 10.0, 1e-6);  // container pts are exact multiples of 1/fps
    EXPECT_EQ(frames[k].image.type(), CV_8UC1);
    EXPECT_EQ(frames[k].image.size(), kSize);
    EXPECT_NEAR(cv::mean(frames[k].image)[0], 10 * k + 5, 2);  // MJPG of a flat image: +-2 levels
  }
}

TEST(VideoFileSource, ExplicitFpsOverridesContainerTimesAndColorModeApplies) {
  test_support::TempDirectory dir;
  const fs::path video = dir.path() / "clip.avi";
  WriteVideo(video, 4, 10.0);
  VideoFileSource source(video, SourceOptions(25.0, false, ColorMode::kColor));
  const std::vector<Frame> frames = ReadAll(source);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_DOUBLE_EQ(frames[3].t_s, 3 / 25.0);
  EXPECT_EQ(frames[3].image.type(), CV_8UC3);
}

TEST(VideoFileSource, TruncatedFileThrowsOrRecordsTheMissingFrames) {
  // An AVI cut at 3/4 keeps its header (20 frames announced, plus several kB of padding that a
  // cut at 1/2 of these tiny frames would reach) but loses the last frames and the index.
  test_support::TempDirectory dir;
  const fs::path video = dir.path() / "cut.avi";
  WriteVideo(video, 20, 10.0);
  fs::resize_file(video, fs::file_size(video) * 3 / 4);

  VideoFileSource strict(video, SourceOptions(0.0, false));
  ASSERT_EQ(strict.SizeHint(), std::optional<size_t>(20));
  std::string message;
  int delivered = 0;
  try {
    while (strict.Next()) ++delivered;
    ADD_FAILURE() << "a truncated video ended without an error";
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_GT(delivered, 0);
  EXPECT_LT(delivered, 20);
  EXPECT_THAT(message, HasSubstr(video.string()));
  EXPECT_THAT(message, HasSubstr("ended after " + std::to_string(delivered) + " of the 20"));
  EXPECT_THAT(message, HasSubstr("--skip-bad-frames"));

  VideoFileSource skipping(video, SourceOptions(0.0, true));
  ::testing::internal::CaptureStderr();
  const std::vector<Frame> frames = ReadAll(skipping);
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(frames.size(), static_cast<size_t>(delivered));
  ASSERT_EQ(skipping.SkippedFrames().size(), 1u);
  EXPECT_EQ(skipping.SkippedFrames()[0].item, "frames " + std::to_string(delivered) + "..19");
  EXPECT_THAT(stderr_text, HasSubstr("warning: "));
  EXPECT_FALSE(skipping.Next().has_value());
}

TEST(VideoFileSource, MissingAndUndecodableFilesNameTheFile) {
  test_support::TempDirectory dir;
  const fs::path missing = dir.path() / "missing.avi";
  EXPECT_THAT(MessageOf<std::runtime_error>([&] { VideoFileSource(missing, SourceOptions(0.0)); }),
              HasSubstr(missing.string()));
  const fs::path garbage = dir.path() / "garbage.avi";
  WriteText(garbage, "not a video");
  ::testing::internal::CaptureStderr();  // OpenCV backends log their failed attempts
  const std::string message =
      MessageOf<std::runtime_error>([&] { VideoFileSource(garbage, SourceOptions(0.0)); });
  ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(message, HasSubstr(garbage.string()));
  EXPECT_THAT(message, HasSubstr("cannot open video"));
}

// Values checked like files (issue 18): a dangling link keeps its place in the sequence (so --fps
// times do not shift) and fails naming itself; a device or FIFO is not "missing"; 16-bit frames
// are not cut to their high byte.
TEST(ImageFolderSource, DanglingSymlinkKeepsItsPlaceAndNamesItsTarget) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 3);
  fs::remove(dir.path() / "frame2.png");
  fs::create_symlink(dir.path() / "gone.png", dir.path() / "frame2.png");
  ImageFolderSource strict(dir.path(), SourceOptions(10.0));
  EXPECT_EQ(strict.SizeHint(), std::optional<size_t>(3));
  ASSERT_TRUE(strict.Next().has_value());
  EXPECT_THAT(
      MessageOf<std::runtime_error>([&] { strict.Next(); }),
      ::testing::AllOf(HasSubstr("frame2.png"), HasSubstr("gone.png"), HasSubstr("symbolic link")));
  ::testing::internal::CaptureStderr();
  ImageFolderSource skipping(dir.path(), SourceOptions(10.0, /*skip=*/true));
  const std::vector<Frame> frames = ReadAll(skipping);
  ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_DOUBLE_EQ(frames[1].t_s, 2 / 10.0);  // frame3 keeps its time: nothing shifted
  EXPECT_EQ(LevelOf(frames[1]), 35);
}

TEST(ImageFolderSource, SixteenBitFramesAreRejectedNotCut) {
  test_support::TempDirectory dir;
  WriteImage(dir.path() / "frame1.png", cv::Mat(kSize, CV_16UC1, cv::Scalar(4095)));
  ImageFolderSource source(dir.path(), SourceOptions(10.0));
  EXPECT_THAT(MessageOf<std::runtime_error>([&] { source.Next(); }),
              ::testing::AllOf(HasSubstr("frame1.png"), HasSubstr("16-bit")));
}

TEST(OpenFrameSource, DeviceOrFifoIsNotAFrameSourceAndSaysSo) {
  EXPECT_THAT(
      MessageOf<std::invalid_argument>([&] { OpenFrameSource("/dev/null", SourceOptions(0.0)); }),
      ::testing::AllOf(HasSubstr("'/dev/null'"), HasSubstr("not a regular file")));
}

// ---------------------------------------------------------------- factory and camera

TEST(OpenFrameSource, DispatchesFolderVideoAndCameraSpecs) {
  test_support::TempDirectory dir;
  WriteSequence(dir.path(), 2);
  const fs::path video = dir.path() / "clip.avi";
  WriteVideo(video, 3, 10.0);
  EXPECT_THAT(OpenFrameSource(dir.path().string(), SourceOptions(10.0))->Describe(),
              HasSubstr("image folder"));
  const std::unique_ptr<FrameSource> video_source =
      OpenFrameSource(video.string(), SourceOptions(0.0));
  EXPECT_THAT(video_source->Describe(), HasSubstr("video file"));
  EXPECT_EQ(ReadAll(*video_source).size(), 3u);

  EXPECT_THAT(MessageOf<std::invalid_argument>([&] {
                OpenFrameSource((dir.path() / "frame1.png").string(), SourceOptions(0.0));
              }),
              HasSubstr("single image"));
  EXPECT_THAT(MessageOf<std::runtime_error>(
                  [&] { OpenFrameSource((dir.path() / "nope").string(), SourceOptions(0.0)); }),
              HasSubstr("camera:<N>"));
  EXPECT_THAT(
      MessageOf<std::invalid_argument>([&] { OpenFrameSource("camera:x", SourceOptions(0.0)); }),
      HasSubstr("camera:<N>"));
  EXPECT_THAT(
      MessageOf<std::invalid_argument>([&] { OpenFrameSource("camera:", SourceOptions(0.0)); }),
      HasSubstr("'camera:'"));
}

TEST(CameraDeviceSource, NonExistentDeviceGivesAClearError) {
  // No machine running the tests has 900 cameras.
  ::testing::internal::CaptureStderr();  // OpenCV's own backend warnings
  const std::string message =
      MessageOf<std::runtime_error>([] { OpenFrameSource("camera:900", FrameSourceOptions{}); });
  ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(message, HasSubstr("cannot open camera:900"));
  EXPECT_THAT(message, HasSubstr("/dev/video"));
}

// ---------------------------------------------------------------- in-process queue

Frame MakePushed(int k) {
  Frame frame;
  frame.t_s = 0.01 * k;
  frame.index = k;
  frame.camera_id = 1;
  frame.image = GrayFrame(k % 20);
  return frame;
}

TEST(InProcessSource, DeliversFramesPushedFromAnotherThreadInOrderThenEnds) {
  FrameSourceOptions options;
  options.color_mode = ColorMode::kColor;
  InProcessSource source(options, "sim camera");
  constexpr int kFrames = 200;
  std::thread producer([&] {
    for (int k = 0; k < kFrames; ++k) source.Push(MakePushed(k));
    source.Close();
  });
  const std::vector<Frame> frames = ReadAll(source);  // may start before the first push
  producer.join();
  ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    EXPECT_EQ(frames[k].index, k);
    EXPECT_DOUBLE_EQ(frames[k].t_s, 0.01 * k);
    EXPECT_EQ(frames[k].camera_id, 1);
    ASSERT_EQ(frames[k].image.type(), CV_8UC3);  // gray pushed, colour requested
    EXPECT_EQ(LevelOf(frames[k]), 10 * (k % 20) + 5);
  }
  EXPECT_FALSE(source.Next().has_value());
  EXPECT_EQ(source.Describe(), "sim camera");
  EXPECT_FALSE(source.SizeHint().has_value());
}

TEST(InProcessSource, RejectsBadPushesInTheProducer) {
  InProcessSource source;
  source.Push(MakePushed(1));
  EXPECT_THAT(MessageOf<std::invalid_argument>([&] { source.Push(MakePushed(1)); }),
              HasSubstr("not after the previous"));
  Frame empty = MakePushed(2);
  empty.image = cv::Mat();
  EXPECT_THAT(MessageOf<std::invalid_argument>([&] { source.Push(empty); }), HasSubstr("empty"));
  Frame resized = MakePushed(3);
  resized.image = GrayFrame(3, cv::Size(8, 8));
  EXPECT_THAT(MessageOf<std::invalid_argument>([&] { source.Push(resized); }),
              HasSubstr("image size"));
  source.Close();
  EXPECT_THAT(MessageOf<std::logic_error>([&] { source.Push(MakePushed(4)); }),
              HasSubstr("after Close()"));
  // The one good frame is still delivered after Close().
  ASSERT_TRUE(source.Next().has_value());
  EXPECT_FALSE(source.Next().has_value());
}

}  // namespace
}  // namespace aperture::perception
