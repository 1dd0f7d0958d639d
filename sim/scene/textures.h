#pragma once
// Surface textures of the simulator. A texture maps surface coordinates (u, v) [m] (see
// primitives.h for each primitive's (u, v)) to an RGB albedo in [0, 1]. Image textures hold
// texels of a known physical size (texel_size_m) and are sampled with bilinear or nearest
// filtering, repeating or clamped at the border; the checkerboard is analytic (exact edges, the
// renderer's supersampling anti-aliases them). Bilinear image textures keep a mip pyramid
// (2 x 2 box averages): a sample whose footprint covers several texels reads the level whose
// texels match the footprint, which removes aliasing (shimmer) of distant textures and keeps
// lookups cache-friendly. Every procedural generator is seeded and
// deterministic: the same arguments give the same texels on every run and thread count.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>
#include <opencv2/core/mat.hpp>

namespace aperture::sim {

using Rgb = Eigen::Vector3f;  // linear RGB albedo or radiance, 1.0 = white

class Texture {
 public:
  enum class Filter { kBilinear, kNearest };
  enum class Wrap { kRepeat, kClamp };

  // Image texture. image_rgb: CV_32FC3 (RGB, [0, 1]) or CV_8UC3 (RGB, 0..255, converted);
  // column index grows with u, row index with v; texel (0, 0) covers u, v in [0, texel_size_m).
  // Throws std::invalid_argument for an empty image, another type or texel_size_m <= 0.
  Texture(const cv::Mat& image_rgb, double texel_size_m, Filter filter = Filter::kBilinear,
          Wrap wrap = Wrap::kRepeat);

  // Analytic checkerboard: squares_x x squares_y squares of square_size_m starting at
  // (u, v) = (margin_m, margin_m), the first square (lowest u and v) dark; everything outside
  // the board has border_color. squares_x = squares_y = 0 makes an infinite checkerboard (no
  // border, margin_m only shifts the pattern). Throws std::invalid_argument for square_size_m
  // <= 0, margin_m < 0 or negative square counts.
  static Texture Checkerboard(double square_size_m, int squares_x = 0, int squares_y = 0,
                              double margin_m = 0.0, const Rgb& dark = Rgb::Constant(0.05f),
                              const Rgb& light = Rgb::Constant(0.95f),
                              const Rgb& border_color = Rgb::Constant(0.95f));

  // Albedo at surface coordinates (u_m, v_m). footprint_m: size of the surface patch one sample
  // stands for [m] (0: finest level); selects the mip level of bilinear image textures.
  Rgb Sample(double u_m, double v_m, double footprint_m = 0.0) const;

  // True when a sample can change abruptly between neighbouring points (analytic checkerboard,
  // nearest filtering); false for bilinear image textures, which the mip level selected by the
  // footprint already band-limits. The renderer supersamples hard-edged textures only.
  bool has_hard_edges() const { return image_.empty() || filter_ == Filter::kNearest; }
  double texel_size_m() const { return texel_size_m_; }
  const cv::Mat& image() const { return image_; }  // CV_32FC3 RGB; empty for a checkerboard

 private:
  Texture() = default;
  void BuildMipLevels();

  // One mip level as Sample reads it (the pixels stay owned by levels_).
  struct MipLevel {
    const float* data;  // rows of channels_ floats per texel (RGB or gray)
    size_t row_floats;  // floats per row (step)
    int cols;
    int rows;
    double inv_cols;
    double inv_rows;
    double texel_m;      // texel size at this level
    double inv_texel_m;
  };

  // Bilinear or nearest sample of one mip level at texel coordinates (x, y) (centres at
  // integers); kChannels = channels_.
  template <int kChannels>
  Rgb SampleLevel(const MipLevel& mip, double x, double y, bool repeat) const;

  cv::Mat image_;
  // levels_[0] = image_ (or its one channel when gray), each next one half the size.
  std::vector<cv::Mat> levels_;
  int channels_ = 3;             // floats per texel in levels_: 1 for a gray image, else 3
  std::vector<MipLevel> mips_;   // one per levels_ entry; empty for a checkerboard
  double texel_size_m_ = 1.0;
  Filter filter_ = Filter::kBilinear;
  Wrap wrap_ = Wrap::kRepeat;
  // Checkerboard (used when image_ is empty).
  int squares_x_ = 0;
  int squares_y_ = 0;
  double margin_m_ = 0.0;
  Rgb dark_ = Rgb::Zero();
  Rgb light_ = Rgb::Ones();
  Rgb border_ = Rgb::Ones();
};

// Parameters shared by the procedural image textures.
struct ProceduralTextureParams {
  int size_px = 256;           // square texture image size [texels]; the texture repeats
  double texel_size_m = 0.01;  // physical texel size: 256 x 1 cm = 2.56 m repeat period
  std::uint64_t seed = 1;      // same seed -> identical texels
};

// Fractal value noise (sum of octaves of bilinearly interpolated lattice noise, tileable),
// blended between color_a (noise 0) and color_b (noise 1). base_period_px: lattice period of
// the coarsest octave [texels]; each further octave halves it with amplitude * persistence.
std::shared_ptr<const Texture> MakeValueNoiseTexture(const ProceduralTextureParams& params,
                                                     int octaves = 5, int base_period_px = 64,
                                                     double persistence = 0.5,
                                                     const Rgb& color_a = Rgb::Constant(0.15f),
                                                     const Rgb& color_b = Rgb::Constant(0.9f));

// 'Newspaper': white page with columns of random black words drawn with cv::putText.
std::shared_ptr<const Texture> MakeNewspaperTexture(const ProceduralTextureParams& params,
                                                    int columns = 3);

// Tree bark: brown, vertically stretched noise with dark furrows (u around the trunk, v up).
std::shared_ptr<const Texture> MakeBarkTexture(const ProceduralTextureParams& params);

// Grass: green value noise with random short blades.
std::shared_ptr<const Texture> MakeGrassTexture(const ProceduralTextureParams& params);

}  // namespace aperture::sim
