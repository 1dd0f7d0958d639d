#include "sim/scene/textures.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "sim/scene/counter_hash.h"

namespace aperture::sim {
namespace {

int WrapIndex(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

void ValidateParams(const ProceduralTextureParams& params, const char* what) {
  if (params.size_px < 8) {
    throw std::invalid_argument(std::string(what) + ": size_px = " +
                                std::to_string(params.size_px) + " must be >= 8");
  }
  if (!(params.texel_size_m > 0.0)) {
    throw std::invalid_argument(std::string(what) + ": texel_size_m = " +
                                std::to_string(params.texel_size_m) + " must be > 0");
  }
}

// Tileable fractal value noise in [0, 1], CV_32FC1 of size x size. The lattice periods of the
// coarsest octave are period_x / period_y texels (clamped so at least one cell fits), halved per
// octave; lattice values are hashed from (seed, octave, cell) and wrap at the image border.
cv::Mat FractalNoise(int size, int period_x, int period_y, int octaves, double persistence,
                     std::uint64_t seed) {
  cv::Mat noise(size, size, CV_32FC1, cv::Scalar(0.0));
  double amplitude = 1.0;
  double total = 0.0;
  for (int octave = 0; octave < octaves; ++octave) {
    const int px = std::max(1, period_x >> octave);
    const int py = std::max(1, period_y >> octave);
    const int cells_x = std::max(1, size / px);
    const int cells_y = std::max(1, size / py);
    const double cell_w = static_cast<double>(size) / cells_x;
    const double cell_h = static_cast<double>(size) / cells_y;
    auto lattice = [&](int cx, int cy) {
      return UniformFromHash(HashCounters(seed, static_cast<std::uint64_t>(octave),
                                          static_cast<std::uint64_t>(WrapIndex(cx, cells_x)),
                                          static_cast<std::uint64_t>(WrapIndex(cy, cells_y))));
    };
    for (int y = 0; y < size; ++y) {
      const double fy = y / cell_h;
      const int cy = static_cast<int>(std::floor(fy));
      double ty = fy - cy;
      ty = ty * ty * (3.0 - 2.0 * ty);  // smoothstep: C1 across lattice cells
      float* row = noise.ptr<float>(y);
      for (int x = 0; x < size; ++x) {
        const double fx = x / cell_w;
        const int cx = static_cast<int>(std::floor(fx));
        double tx = fx - cx;
        tx = tx * tx * (3.0 - 2.0 * tx);
        const double top = lattice(cx, cy) * (1.0 - tx) + lattice(cx + 1, cy) * tx;
        const double bottom = lattice(cx, cy + 1) * (1.0 - tx) + lattice(cx + 1, cy + 1) * tx;
        row[x] += static_cast<float>(amplitude * (top * (1.0 - ty) + bottom * ty));
      }
    }
    total += amplitude;
    amplitude *= persistence;
  }
  noise *= 1.0 / total;
  return noise;
}

// Blends two colours by a CV_32FC1 weight image into a CV_32FC3 RGB image.
cv::Mat Blend(const cv::Mat& weight, const Rgb& a, const Rgb& b) {
  cv::Mat out(weight.size(), CV_32FC3);
  for (int y = 0; y < weight.rows; ++y) {
    const float* w = weight.ptr<float>(y);
    cv::Vec3f* o = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < weight.cols; ++x) {
      const Rgb c = a + (b - a) * std::clamp(w[x], 0.0f, 1.0f);
      o[x] = cv::Vec3f(c.x(), c.y(), c.z());
    }
  }
  return out;
}

}  // namespace

Texture::Texture(const cv::Mat& image_rgb, double texel_size_m, Filter filter, Wrap wrap)
    : texel_size_m_(texel_size_m), filter_(filter), wrap_(wrap) {
  if (image_rgb.empty()) {
    throw std::invalid_argument("Texture: image is empty; pass a CV_32FC3 or CV_8UC3 RGB image");
  }
  if (image_rgb.type() == CV_32FC3) {
    image_ = image_rgb.clone();
  } else if (image_rgb.type() == CV_8UC3) {
    image_rgb.convertTo(image_, CV_32FC3, 1.0 / 255.0);
  } else {
    throw std::invalid_argument("Texture: image type " + std::to_string(image_rgb.type()) +
                                " unsupported; pass CV_32FC3 or CV_8UC3 RGB");
  }
  if (!(texel_size_m > 0.0)) {
    throw std::invalid_argument("Texture: texel_size_m = " + std::to_string(texel_size_m) +
                                " must be > 0");
  }
  BuildMipLevels();
}

void Texture::BuildMipLevels() {
  // Gray images (R = G = B in every texel, e.g. value noise between gray colours) keep one
  // channel: a third of the memory a frame streams through, and the same samples.
  std::vector<cv::Mat> rgb;
  cv::split(image_, rgb);
  const bool gray =
      cv::countNonZero(rgb[0] != rgb[1]) == 0 && cv::countNonZero(rgb[0] != rgb[2]) == 0;
  channels_ = gray ? 1 : 3;
  levels_ = {gray ? rgb[0] : image_};
  // Nearest textures (tags) stay exact: level 0 only.
  while (filter_ == Filter::kBilinear && levels_.back().cols >= 2 && levels_.back().rows >= 2 && levels_.back().cols % 2 == 0 &&
         levels_.back().rows % 2 == 0) {
    cv::Mat next;
    // An exact 2:1 INTER_AREA resize is the 2 x 2 box average (no wrap needed: sizes are even).
    cv::resize(levels_.back(), next, cv::Size(levels_.back().cols / 2, levels_.back().rows / 2), 0,
               0, cv::INTER_AREA);
    levels_.push_back(next);
  }
  double texel = texel_size_m_;
  for (const cv::Mat& level : levels_) {
    mips_.push_back(MipLevel{level.ptr<float>(), level.step1(), level.cols, level.rows,
                             1.0 / level.cols, 1.0 / level.rows, texel, 1.0 / texel});
    texel *= 2.0;
  }
}

Texture Texture::Checkerboard(double square_size_m, int squares_x, int squares_y,
                              double margin_m, const Rgb& dark, const Rgb& light,
                              const Rgb& border_color) {
  if (!(square_size_m > 0.0) || !(margin_m >= 0.0) || squares_x < 0 || squares_y < 0) {
    throw std::invalid_argument(
        "Texture::Checkerboard: need square_size_m > 0 (got " + std::to_string(square_size_m) +
        "), margin_m >= 0 (got " + std::to_string(margin_m) + ") and square counts >= 0 (got " +
        std::to_string(squares_x) + " x " + std::to_string(squares_y) + ")");
  }
  Texture t;
  t.texel_size_m_ = square_size_m;
  t.squares_x_ = squares_x;
  t.squares_y_ = squares_y;
  t.margin_m_ = margin_m;
  t.dark_ = dark;
  t.light_ = light;
  t.border_ = border_color;
  return t;
}

namespace {

// Texel index pair (i0, i1 = next texel) and weight of i1 for texel coordinate x (texel centres
// at integers), wrapped or clamped to [0, n).
struct TexelSpan {
  int i0;
  int i1;
  float w1;
};

// floor for |x| < 2^63 without a libm call (baseline x86-64 has no SSE4.1 round instruction).
inline double FastFloor(double x) {
  const double t = static_cast<double>(static_cast<long long>(x));
  return t > x ? t - 1.0 : t;
}

// inv_n = 1.0 / n.
inline TexelSpan Span(double x, int n, double inv_n, bool repeat) {
  const double fx = FastFloor(x);
  TexelSpan s;
  s.w1 = static_cast<float>(x - fx);
  if (repeat) {
    // One floating-point wrap instead of two integer modulos per sample.
    const double wrapped = fx - n * FastFloor(fx * inv_n);
    s.i0 = std::clamp(static_cast<int>(wrapped), 0, n - 1);
    s.i1 = s.i0 + 1 == n ? 0 : s.i0 + 1;
  } else {
    s.i0 = static_cast<int>(std::clamp(fx, 0.0, n - 1.0));
    s.i1 = static_cast<int>(std::clamp(fx + 1.0, 0.0, n - 1.0));
  }
  return s;
}

}  // namespace

Rgb Texture::Sample(double u_m, double v_m, double footprint_m) const {
  if (mips_.empty()) {
    const double su = (u_m - margin_m_) / texel_size_m_;
    const double sv = (v_m - margin_m_) / texel_size_m_;
    const double iu = FastFloor(su);
    const double iv = FastFloor(sv);
    const bool bounded = squares_x_ > 0 && squares_y_ > 0;
    if (bounded && (iu < 0.0 || iv < 0.0 || iu >= squares_x_ || iv >= squares_y_)) {
      return border_;
    }
    const bool even = (static_cast<long long>(iu) + static_cast<long long>(iv)) % 2 == 0;
    return even ? dark_ : light_;
  }
  const bool repeat = wrap_ == Wrap::kRepeat;
  // Finest level whose texels are at least the footprint / 2 (nearest textures: level 0 only).
  size_t level = 0;
  while (level + 1 < mips_.size() && footprint_m >= 2.0 * mips_[level].texel_m) ++level;
  const MipLevel& mip = mips_[level];
  // Texel centres sit at (i + 0.5) * texel.
  const double x = u_m * mip.inv_texel_m - 0.5;
  const double y = v_m * mip.inv_texel_m - 0.5;
  return channels_ == 1 ? SampleLevel<1>(mip, x, y, repeat) : SampleLevel<3>(mip, x, y, repeat);
}

template <int kChannels>
Rgb Texture::SampleLevel(const MipLevel& mip, double x, double y, bool repeat) const {
  // Gray levels hold one float per texel, the same value in R, G and B.
  const auto texel = [](const float* t) {
    return kChannels == 1 ? Rgb(Rgb::Constant(t[0])) : Rgb(t[0], t[1], t[2]);
  };
  if (filter_ == Filter::kNearest) {
    const TexelSpan sx = Span(FastFloor(x + 0.5), mip.cols, mip.inv_cols, repeat);
    const TexelSpan sy = Span(FastFloor(y + 0.5), mip.rows, mip.inv_rows, repeat);
    return texel(mip.data + sy.i0 * mip.row_floats + kChannels * sx.i0);
  }
  const TexelSpan sx = Span(x, mip.cols, mip.inv_cols, repeat);
  const TexelSpan sy = Span(y, mip.rows, mip.inv_rows, repeat);
  const float* row0 = mip.data + sy.i0 * mip.row_floats;
  const float* row1 = mip.data + sy.i1 * mip.row_floats;
  if constexpr (kChannels == 1) {
    const float top = row0[sx.i0] + (row0[sx.i1] - row0[sx.i0]) * sx.w1;
    const float bottom = row1[sx.i0] + (row1[sx.i1] - row1[sx.i0]) * sx.w1;
    return Rgb::Constant(top + (bottom - top) * sy.w1);
  } else {
    const Eigen::Map<const Rgb> t00(row0 + 3 * sx.i0), t01(row0 + 3 * sx.i1);
    const Eigen::Map<const Rgb> t10(row1 + 3 * sx.i0), t11(row1 + 3 * sx.i1);
    const Rgb top = t00 + (t01 - t00) * sx.w1;
    const Rgb bottom = t10 + (t11 - t10) * sx.w1;
    return top + (bottom - top) * sy.w1;
  }
}

std::shared_ptr<const Texture> MakeValueNoiseTexture(const ProceduralTextureParams& params,
                                                     int octaves, int base_period_px,
                                                     double persistence, const Rgb& color_a,
                                                     const Rgb& color_b) {
  ValidateParams(params, "MakeValueNoiseTexture");
  if (octaves < 1 || base_period_px < 1) {
    throw std::invalid_argument("MakeValueNoiseTexture: octaves (" + std::to_string(octaves) +
                                ") and base_period_px (" + std::to_string(base_period_px) +
                                ") must be >= 1");
  }
  const cv::Mat noise = FractalNoise(params.size_px, base_period_px, base_period_px, octaves,
                                     persistence, params.seed);
  return std::make_shared<const Texture>(Blend(noise, color_a, color_b), params.texel_size_m);
}

std::shared_ptr<const Texture> MakeNewspaperTexture(const ProceduralTextureParams& params,
                                                    int columns) {
  ValidateParams(params, "MakeNewspaperTexture");
  if (columns < 1) {
    throw std::invalid_argument("MakeNewspaperTexture: columns = " + std::to_string(columns) +
                                " must be >= 1");
  }
  const int size = params.size_px;
  cv::Mat page(size, size, CV_8UC3, cv::Scalar(235, 235, 228));
  cv::RNG rng(params.seed);  // cv::RNG is a seeded multiply-with-carry generator: deterministic
  const double font_scale = 0.35;
  int baseline = 0;
  const cv::Size glyph = cv::getTextSize("M", cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline);
  const int line_height = glyph.height + baseline + 2;
  const int gutter = std::max(4, size / 40);
  const int column_width = (size - gutter * (columns + 1)) / columns;
  for (int column = 0; column < columns; ++column) {
    const int x0 = gutter + column * (column_width + gutter);
    for (int y = gutter + glyph.height; y < size - gutter; y += line_height) {
      int x = x0;
      while (true) {
        std::string word(static_cast<size_t>(rng.uniform(1, 9)), 'a');
        for (char& ch : word) ch = static_cast<char>('a' + rng.uniform(0, 26));
        const int width = cv::getTextSize(word, cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline).width;
        if (x + width > x0 + column_width) break;
        cv::putText(page, word, cv::Point(x, y), cv::FONT_HERSHEY_SIMPLEX, font_scale,
                    cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
        x += width + glyph.width / 2;
      }
    }
  }
  return std::make_shared<const Texture>(page, params.texel_size_m);
}

std::shared_ptr<const Texture> MakeBarkTexture(const ProceduralTextureParams& params) {
  ValidateParams(params, "MakeBarkTexture");
  // Fine across the trunk (u), coarse along it (v): elongated vertical ridges.
  cv::Mat ridges = FractalNoise(params.size_px, 8, 64, 4, 0.5, params.seed);
  const cv::Mat detail = FractalNoise(params.size_px, 16, 16, 3, 0.5, MixBits(params.seed));
  cv::Mat shade(ridges.size(), CV_32FC1);
  for (int y = 0; y < shade.rows; ++y) {
    for (int x = 0; x < shade.cols; ++x) {
      const float r = ridges.at<float>(y, x);
      const float furrow = r < 0.42f ? 0.25f : 1.0f;  // deep dark furrows between ridges
      shade.at<float>(y, x) = furrow * (0.55f + 0.45f * detail.at<float>(y, x));
    }
  }
  return std::make_shared<const Texture>(Blend(shade, Rgb(0.08f, 0.05f, 0.03f),
                                               Rgb(0.45f, 0.33f, 0.22f)),
                                         params.texel_size_m);
}

std::shared_ptr<const Texture> MakeGrassTexture(const ProceduralTextureParams& params) {
  ValidateParams(params, "MakeGrassTexture");
  const cv::Mat noise = FractalNoise(params.size_px, 32, 32, 4, 0.55, params.seed);
  cv::Mat image = Blend(noise, Rgb(0.10f, 0.25f, 0.06f), Rgb(0.35f, 0.55f, 0.18f));
  cv::RNG rng(MixBits(params.seed));
  const int blades = params.size_px * params.size_px / 24;
  for (int i = 0; i < blades; ++i) {
    const cv::Point2f base(rng.uniform(0.0f, static_cast<float>(params.size_px)),
                           rng.uniform(0.0f, static_cast<float>(params.size_px)));
    const float length = rng.uniform(3.0f, 10.0f);
    const float angle = rng.uniform(-0.5f, 0.5f);
    const cv::Point2f tip = base + cv::Point2f(length * std::sin(angle), -length * std::cos(angle));
    const float g = rng.uniform(0.3f, 0.75f);
    cv::line(image, base, tip, cv::Scalar(0.35f * g, g, 0.15f * g), 1, cv::LINE_AA);
  }
  return std::make_shared<const Texture>(image, params.texel_size_m);
}

}  // namespace aperture::sim
