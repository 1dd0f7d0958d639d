#include "sim/render/camera_effects.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "sim/scene/counter_hash.h"

namespace aperture::sim {
namespace {

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("CameraEffectsParams.") + field + " = " +
                                std::to_string(value) + " " + rule);
  }
}

}  // namespace

CameraEffects::CameraEffects(const CameraEffectsParams& params) : params_(params) {
  Require(params.gain > 0.0 && std::isfinite(params.gain), "gain", params.gain, "must be > 0");
  Require(params.full_well_electrons >= 0.0, "full_well_electrons", params.full_well_electrons,
          "must be >= 0 (0 disables shot noise)");
  Require(params.read_noise_sigma >= 0.0, "read_noise_sigma", params.read_noise_sigma,
          "must be >= 0");
  Require(params.exposure_s >= 0.0, "exposure_s", params.exposure_s, "must be >= 0");
  Require(params.motion_blur_subframes >= 1, "motion_blur_subframes",
          params.motion_blur_subframes, "must be >= 1");
  Require(params.infrared_reflectance_scale >= 0.0f, "infrared_reflectance_scale",
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
  const bool shot = params_.full_well_electrons > 0.0;
  const bool read = params_.read_noise_sigma > 0.0;
  const std::uint64_t frame_seed = HashCounters(params_.seed, static_cast<std::uint64_t>(frame_index));
  const double gain = params_.gain;
  const double read_variance = read ? params_.read_noise_sigma * params_.read_noise_sigma : 0.0;
  const double inv_full_well = shot ? 1.0 / params_.full_well_electrons : 0.0;
  tbb::parallel_for(tbb::blocked_range<int>(0, radiance.rows), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const float* in = radiance.ptr<float>(y);
      uint8_t* out = image.ptr<uint8_t>(y);
      // Box-Muller gives two independent normals per hash: values 2j and 2j + 1 share one.
      const std::uint64_t row_seed = HashCounters(frame_seed, static_cast<std::uint64_t>(y));
      float normals[2] = {0.0f, 0.0f};
      for (int i = 0; i < values_per_row; ++i) {
        double v = in[i];
        if (shot || read) {
          if (i % 2 == 0) {
            NormalPairFromHashF(MixBits(row_seed ^ static_cast<std::uint64_t>(i / 2)), &normals[0],
                                &normals[1]);
          }
          v += std::sqrt(static_cast<float>(read_variance + std::max(v, 0.0) * inv_full_well)) *
               normals[i % 2];
        }
        // In [0, 255] after the clamp: + 0.5 and truncation round to nearest like lround.
        out[i] = static_cast<uint8_t>(std::clamp(gain * v, 0.0, 1.0) * 255.0 + 0.5);
      }
    }
  });
  return image;
}

CapturedFrame CameraEffects::Capture(RayCaster& ray_caster, const Scene& scene,
                                     const perception::CameraModel& camera,
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
    ray_caster.Render(scene, camera, T_WC_at(t), sub_options, &sub);
    if (i == 0) {
      captured.radiance = sub.radiance.clone();
    } else {
      captured.radiance += sub.radiance;
    }
    if (sub_options.ground_truth) {
      captured.depth_C = sub.depth_C.clone();
      captured.object_id = sub.object_id.clone();
    }
  }
  if (n > 1) captured.radiance *= 1.0 / n;
  captured.frame.t_s = t_mid_s;
  captured.frame.index = frame_index;
  captured.frame.image = ToImage8U(captured.radiance, frame_index);
  return captured;
}

}  // namespace aperture::sim
