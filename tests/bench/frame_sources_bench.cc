// Cost of reading one image-sequence frame with the truncation check (ReadImageFile) against a
// bare cv::imread of the same file, for a 752x480 (WVGA) gray PNG and JPEG; and the check alone.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/io/image_file_reader.h"

namespace aperture::perception {
namespace {

cv::Mat MakeImage() {
  cv::Mat gray(480, 752, CV_8UC1);
  cv::randu(gray, 0, 256);
  cv::GaussianBlur(gray, gray, cv::Size(), 2.0);
  return gray;
}

// Writes the test image as `extension` into a fresh temp file, removed on destruction.
class BenchImageFile {
 public:
  explicit BenchImageFile(const std::string& extension)
      : path_(std::filesystem::temp_directory_path() /
              ("aperture_frame_sources_bench_" + std::to_string(::getpid()) + extension)) {
    cv::imwrite(path_.string(), MakeImage());
  }
  ~BenchImageFile() { std::filesystem::remove(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void BM_ReadImageFile(benchmark::State& state, const std::string& extension) {
  const BenchImageFile file(extension);
  for (auto _ : state) benchmark::DoNotOptimize(ReadImageFile(file.path(), ColorMode::kGray));
}
BENCHMARK_CAPTURE(BM_ReadImageFile, png, std::string(".png"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReadImageFile, jpg, std::string(".jpg"))->Unit(benchmark::kMicrosecond);

void BM_ImreadBaseline(benchmark::State& state, const std::string& extension) {
  const BenchImageFile file(extension);
  for (auto _ : state) {
    benchmark::DoNotOptimize(cv::imread(file.path().string(), cv::IMREAD_GRAYSCALE));
  }
}
BENCHMARK_CAPTURE(BM_ImreadBaseline, png, std::string(".png"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ImreadBaseline, jpg, std::string(".jpg"))->Unit(benchmark::kMicrosecond);

void BM_FindTruncation(benchmark::State& state, const std::string& extension) {
  std::vector<unsigned char> bytes;
  cv::imencode(extension, MakeImage(), bytes);
  for (auto _ : state) benchmark::DoNotOptimize(FindTruncation(bytes));
}
BENCHMARK_CAPTURE(BM_FindTruncation, png, std::string(".png"))->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_FindTruncation, jpg, std::string(".jpg"))->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace aperture::perception
