#include "perception/gap/canny_edge_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <sstream>
#include <stdexcept>

namespace aperture::perception {
namespace {

// tan(22.5 deg) in Q15, the sector boundary of cv::Canny's non-maximum suppression.
constexpr int kShift = 15;
constexpr int kTan22 = static_cast<int>(0.4142135623730950488016887242097 * (1 << kShift) + 0.5);

// 3x3 Sobel dx, dy and |dx| + |dy| of columns [begin, end) whose left and right neighbours exist.
// 16-bit lanes suffice (|dx| + |dy| <= 2040); restrict lets the compiler vectorize.
void SobelRow(const uint8_t* __restrict up, const uint8_t* __restrict mid, const uint8_t* __restrict down,
              int begin, int end, int16_t* __restrict gx, int16_t* __restrict gy, int16_t* __restrict mag) {
  for (int x = begin; x < end; ++x) {
    const int16_t sx = static_cast<int16_t>((up[x + 1] - up[x - 1]) + 2 * (mid[x + 1] - mid[x - 1]) +
                                            (down[x + 1] - down[x - 1]));
    const int16_t sy = static_cast<int16_t>((down[x - 1] + 2 * down[x] + down[x + 1]) -
                                            (up[x - 1] + 2 * up[x] + up[x + 1]));
    gx[x] = sx;
    gy[x] = sy;
    mag[x] = static_cast<int16_t>((sx < 0 ? -sx : sx) + (sy < 0 ? -sy : sy));
  }
}

}  // namespace

bool CannyEdgeDetector::IsCandidate(int i) const {
  const int m = magnitude_[i];
  if (m <= low_) return false;
  const int xs = dx_[i];
  const int ys = dy_[i];
  const int x = std::abs(xs);
  const int y = std::abs(ys) << kShift;
  const int tg22x = x * kTan22;
  if (y < tg22x) return m > magnitude_[i - 1] && m >= magnitude_[i + 1];  // gradient ~horizontal
  const int tg67x = tg22x + (x << (kShift + 1));
  if (y > tg67x) return m > magnitude_[i - stride_] && m >= magnitude_[i + stride_];  // ~vertical
  const int s = (xs ^ ys) < 0 ? -1 : 1;  // diagonal
  return m > magnitude_[i - stride_ - s] && m > magnitude_[i + stride_ + s];
}

void CannyEdgeDetector::Grow(int seed) {
  state_[seed] = 2;
  edge_indices_.push_back(seed);
  stack_.push_back(seed);
  const int offsets[8] = {-1, 1, -stride_ - 1, -stride_, -stride_ + 1, stride_ - 1, stride_, stride_ + 1};
  while (!stack_.empty()) {
    const int i = stack_.back();
    stack_.pop_back();
    for (const int offset : offsets) {
      const int j = i + offset;
      if (state_[j] != 0) continue;
      if (IsCandidate(j)) {
        state_[j] = 2;
        edge_indices_.push_back(j);
        stack_.push_back(j);
      } else {
        state_[j] = 1;
      }
    }
  }
}

void CannyEdgeDetector::Detect(const cv::Mat& gray, const cv::Rect& roi, double low_threshold,
                               double high_threshold, bool dilate_3x3, cv::Mat* edges) {
  if (gray.type() != CV_8UC1 || roi.width < 1 || roi.height < 1 ||
      (roi & cv::Rect(0, 0, gray.cols, gray.rows)) != roi) {
    std::ostringstream s;
    s << "CannyEdgeDetector: image " << gray.cols << "x" << gray.rows << " type " << gray.type()
      << " with roi (" << roi.x << ", " << roi.y << ", " << roi.width << "x" << roi.height << "); expected CV_8UC1 and a non-empty roi inside the image";
    throw std::invalid_argument(s.str());
  }
  if (low_threshold > high_threshold) std::swap(low_threshold, high_threshold);  // as cv::Canny
  low_ = static_cast<int>(std::floor(low_threshold));
  high_ = static_cast<int>(std::floor(high_threshold));
  width_ = roi.width;
  height_ = roi.height;
  stride_ = width_ + 2;
  const size_t padded = static_cast<size_t>(stride_) * (height_ + 2);
  dx_.resize(padded);
  dy_.resize(padded);
  magnitude_.resize(padded);
  state_.resize(padded);

  // Gradient pass: 3x3 Sobel with the ROI's border replicated (cv::Canny treats gray(roi) as an
  // image of its own), L1 magnitude. Columns with both neighbours inside the ROI go through a
  // branch-free loop the compiler vectorizes; the first and last column are done apart.
  const cv::Mat image = gray(roi);
  std::memset(magnitude_.data(), 0, sizeof(int16_t) * stride_);
  std::memset(magnitude_.data() + padded - stride_, 0, sizeof(int16_t) * stride_);
  for (int y = 0; y < height_; ++y) {
    const uint8_t* up = image.ptr<uint8_t>(std::max(y - 1, 0));
    const uint8_t* mid = image.ptr<uint8_t>(y);
    const uint8_t* down = image.ptr<uint8_t>(std::min(y + 1, height_ - 1));
    const int row = (y + 1) * stride_ + 1;  // padded index of column 0
    int16_t* gx = dx_.data() + row;
    int16_t* gy = dy_.data() + row;
    int16_t* mag = magnitude_.data() + row;
    const auto pixel = [&](int x, int xm, int xp) {
      const int sx = (up[xp] - up[xm]) + 2 * (mid[xp] - mid[xm]) + (down[xp] - down[xm]);
      const int sy = (down[xm] + 2 * down[x] + down[xp]) - (up[xm] + 2 * up[x] + up[xp]);
      gx[x] = static_cast<int16_t>(sx);
      gy[x] = static_cast<int16_t>(sy);
      mag[x] = static_cast<int16_t>(std::abs(sx) + std::abs(sy));
    };
    const int last = width_ - 1;
    pixel(0, 0, std::min(1, last));
    SobelRow(up, mid, down, 1, last, gx, gy, mag);
    if (last > 0) pixel(last, last - 1, last);
    mag[-1] = 0;
    mag[width_] = 0;
  }

  std::memset(state_.data(), 0, padded);
  std::memset(state_.data(), 1, stride_);
  std::memset(state_.data() + padded - stride_, 1, stride_);
  for (int r = 1; r <= height_; ++r) {
    state_[r * stride_] = 1;
    state_[r * stride_ + stride_ - 1] = 1;
  }

  // Seeds: strong candidates, found 16 pixels at a time (SSE2 compare + bit mask; most pixels
  // of a textured image are below the high threshold).
  edge_indices_.clear();
  const auto seed = [this](int i) {
    if (state_[i] != 0) return;
    if (IsCandidate(i)) {
      Grow(i);
    } else {
      state_[i] = 1;
    }
  };
  for (int r = 1; r <= height_; ++r) {
    const int row_begin = r * stride_ + 1;
    const int row_end = row_begin + width_;
    int i = row_begin;
#if defined(__SSE2__)
    const __m128i high = _mm_set1_epi16(static_cast<int16_t>(std::clamp(high_, -32768, 32767)));
    for (; i + 16 <= row_end; i += 16) {
      const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(magnitude_.data() + i));
      const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(magnitude_.data() + i + 8));
      unsigned mask = static_cast<unsigned>(
          _mm_movemask_epi8(_mm_packs_epi16(_mm_cmpgt_epi16(a, high), _mm_cmpgt_epi16(b, high))));
      while (mask != 0) {
        seed(i + __builtin_ctz(mask));
        mask &= mask - 1;
      }
    }
#endif
    for (; i < row_end; ++i) {
      if (magnitude_[i] > high_) seed(i);
    }
  }

  // Output through a padded buffer: the 3x3 dilation writes need no clipping and no division
  // back to (row, column); the padding is dropped by the row copies.
  output_.assign(padded, 0);
  if (dilate_3x3) {
    const int offsets[9] = {-stride_ - 1, -stride_, -stride_ + 1, -1, 0, 1, stride_ - 1, stride_, stride_ + 1};
    for (const int i : edge_indices_) {
      for (const int offset : offsets) output_[i + offset] = 255;
    }
  } else {
    for (const int i : edge_indices_) output_[i] = 255;
  }
  edges->create(roi.height, roi.width, CV_8UC1);
  for (int y = 0; y < height_; ++y) {
    std::memcpy(edges->ptr<uint8_t>(y), output_.data() + (y + 1) * stride_ + 1, width_);
  }
}

}  // namespace aperture::perception
