#include "sim/render/camera_effects.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "control/require.h"
#include "perception/cpu_time.h"
#include "sim/render/render_profile.h"
#include "sim/scene/counter_hash.h"

namespace aperture::sim {
namespace {

// Standard normal samples for sensor noise: a table of kNormalTableSize values at the
// stratified quantiles Phi^-1((i + 0.5) / kNormalTableSize), rescaled to unit variance (the
// stratification cuts the tails at |x| = 3.67 sigma and would leave the variance 0.03 % short;
// kurtosis 2.99 instead of 3). Each 64-bit hash yields kIndicesPerHash independent uniform 12-bit
// indices, so a value costs a fifth of a hash and one L1 load instead of a log, a sqrt and a sincos
// (Box-Muller).
constexpr int kNormalTableBits = 12;
constexpr int kNormalTableSize = 1 << kNormalTableBits;
constexpr int kIndicesPerHash = 64 / kNormalTableBits;

std::array<float, kNormalTableSize> MakeStandardNormalTable() {
  std::array<double, kNormalTableSize> quantiles;
  double sum_squares = 0.0;
  for (int i = 0; i < kNormalTableSize; ++i) {
    const double p = (i + 0.5) / kNormalTableSize;
    // Phi(x) = erfc(-x / sqrt 2) / 2 is increasing: bisection to double precision.
    double lo = -10.0, hi = 10.0;
    for (int k = 0; k < 64; ++k) {
      const double mid = 0.5 * (lo + hi);
      (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
    }
    quantiles[i] = 0.5 * (lo + hi);
    sum_squares += quantiles[i] * quantiles[i];
  }
  const double unit_variance = 1.0 / std::sqrt(sum_squares / kNormalTableSize);
  std::array<float, kNormalTableSize> table;
  for (int i = 0; i < kNormalTableSize; ++i) {
    table[i] = static_cast<float>(quantiles[i] * unit_variance);
  }
  return table;
}

const std::array<float, kNormalTableSize>& StandardNormalTable() {
  static const std::array<float, kNormalTableSize> table = MakeStandardNormalTable();
  return table;
}

// One row's normals: value i takes bits [12 k, 12 k + 12) of hash (row_seed, i / 5), k = i % 5.
void FillNormals(std::uint64_t row_seed, const std::array<float, kNormalTableSize>& table,
                 Eigen::ArrayXf* normals) {
  const int n = static_cast<int>(normals->size());
  for (int i = 0; i < n; i += kIndicesPerHash) {
    std::uint64_t h = MixBits(row_seed ^ static_cast<std::uint64_t>(i / kIndicesPerHash));
    const int end = std::min(n, i + kIndicesPerHash);
    for (int j = i; j < end; ++j, h >>= kNormalTableBits) {
      (*normals)[j] = table[h & (kNormalTableSize - 1)];
    }
  }
}

}  // namespace

CameraEffects::CameraEffects(const CameraEffectsParams& params) : params_(params) {
  control::Require(params.gain > 0.0 && std::isfinite(params.gain), "CameraEffectsParams.gain",
                   params.gain, "must be > 0");
  control::Require(params.full_well_electrons >= 0.0, "CameraEffectsParams.full_well_electrons",
                   params.full_well_electrons, "must be >= 0 (0 disables shot noise)");
  control::Require(params.read_noise_sigma >= 0.0, "CameraEffectsParams.read_noise_sigma",
                   params.read_noise_sigma, "must be >= 0");
  control::Require(params.exposure_s >= 0.0, "CameraEffectsParams.exposure_s", params.exposure_s,
                   "must be >= 0");
  control::Require(params.motion_blur_subframes >= 1, "CameraEffectsParams.motion_blur_subframes",
                   params.motion_blur_subframes, "must be >= 1");
  control::Require(params.infrared_reflectance_scale >= 0.0f,
                   "CameraEffectsParams.infrared_reflectance_scale",
                   params.infrared_reflectance_scale, "must be >= 0");
}

cv::Mat CameraEffects::ToImage8U(const cv::Mat& radiance, int frame_index) const {
  if (radiance.type() != CV_32FC1 && radiance.type() != CV_32FC3) {
    throw std::invalid_argument("CameraEffects::ToImage8U: radiance type " +
                                std::to_string(radiance.type()) + " unsupported; pass CV_32FC1/3");
  }
  const int channels = radiance.channels();
  cv::Mat image(radiance.size(), channels == 1 ? CV_8UC1 : CV_8UC3);
  const int values_per_row = radiance.cols * channels;
  const bool noisy = params_.full_well_electrons > 0.0 || params_.read_noise_sigma > 0.0;
  const std::uint64_t frame_seed =
      HashCounters(params_.seed, static_cast<std::uint64_t>(frame_index));
  // Single precision throughout: 8-bit output needs ~1e-3 relative, and Eigen's packet sqrt
  // handles several values per instruction.
  const float scale = static_cast<float>(params_.gain * 255.0);
  const float read_variance =
      static_cast<float>(params_.read_noise_sigma * params_.read_noise_sigma);
  const float inv_full_well = params_.full_well_electrons > 0.0
                                  ? static_cast<float>(1.0 / params_.full_well_electrons)
                                  : 0.0f;
  const std::array<float, kNormalTableSize>& normal_table = StandardNormalTable();
  tbb::parallel_for(
      tbb::blocked_range<int>(0, radiance.rows), [&](const tbb::blocked_range<int>& rows) {
        Eigen::ArrayXf normals(values_per_row);
        Eigen::ArrayXf scaled(values_per_row);
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const Eigen::Map<const Eigen::ArrayXf> v(radiance.ptr<float>(y), values_per_row);
          if (noisy) {
            FillNormals(HashCounters(frame_seed, static_cast<std::uint64_t>(y)), normal_table,
                        &normals);
            // signal + sqrt(read^2 + signal / full_well) * N(0, 1), in 8-bit units.
            scaled = (v + (v.max(0.0f) * inv_full_well + read_variance).sqrt() * normals) * scale;
          } else {
            scaled = v * scale;
          }
          // Clamped to [0, 255]: + 0.5 and truncation round to nearest like lround.
          scaled = scaled.max(0.0f).min(255.0f) + 0.5f;
          std::uint8_t* out = image.ptr<std::uint8_t>(y);
          for (int i = 0; i < values_per_row; ++i) out[i] = static_cast<std::uint8_t>(scaled[i]);
        }
      });
  return image;
}

CapturedFrame CameraEffects::Capture(RayCaster& ray_caster, const Scene& scene,
                                     const perception::CameraModel& camera,
                                     const std::function<Eigen::Isometry3d(double)>& T_WC_at,
                                     double t_mid_s, int frame_index,
                                     const RenderOptions& options) const {
  return Capture(
      [&](const Eigen::Isometry3d& T_WC, const RenderOptions& render_options, RenderOutput* out) {
        ray_caster.Render(scene, camera, T_WC, render_options, out);
      },
      T_WC_at, t_mid_s, frame_index, options);
}

CapturedFrame CameraEffects::Capture(const RenderFunction& render,
                                     const std::function<Eigen::Isometry3d(double)>& T_WC_at,
                                     double t_mid_s, int frame_index,
                                     const RenderOptions& options) const {
  RenderOptions render_options = options;
  if (params_.infrared) render_options.reflectance_scale = params_.infrared_reflectance_scale;
  const int n = params_.motion_blur_subframes;
  const int ground_truth_subframe = (n - 1) / 2;  // the subframe nearest t_mid
  CapturedFrame captured;
  RenderOutput sub;
  for (int i = 0; i < n; ++i) {
    const double t = t_mid_s + params_.exposure_s * ((i + 0.5) / n - 0.5);
    RenderOptions sub_options = render_options;
    sub_options.ground_truth = options.ground_truth && i == ground_truth_subframe;
    render(T_WC_at(t), sub_options, &sub);
    const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::blur_s));
    // Render reuses sub's buffers: copies only while another subframe follows.
    const bool last = i == n - 1;
    if (i == 0) {
      captured.radiance = last ? sub.radiance : sub.radiance.clone();
    } else {
      captured.radiance += sub.radiance;
    }
    if (sub_options.ground_truth) {
      captured.depth_C = last ? sub.depth_C : sub.depth_C.clone();
      captured.object_id = last ? sub.object_id : sub.object_id.clone();
    }
  }
  if (n > 1) {
    const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::blur_s));
    captured.radiance *= 1.0 / n;
  }
  captured.frame.t_s = t_mid_s;
  captured.frame.index = frame_index;
  const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::noise_s));
  captured.frame.image = ToImage8U(captured.radiance, frame_index);
  return captured;
}

}  // namespace aperture::sim
