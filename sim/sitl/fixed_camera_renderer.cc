#include "sim/sitl/fixed_camera_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "perception/camera/pinhole_camera.h"
#include "sim/scene/primitives.h"

namespace aperture::sim {
namespace {

// Beyond an object's projection (and an LED's blob window, kLedWindowSigmas): adaptive
// supersampling looks one pixel further, texture footprints one pixel too.
constexpr int kNeighbourMarginPx = 2;

void CopyRegion(const RenderOutput& from, const cv::Rect& from_region, const cv::Rect& to_region,
                RenderOutput* to) {
  from.radiance(from_region).copyTo(to->radiance(to_region));
  if (!from.depth_C.empty()) {
    from.depth_C(from_region).copyTo(to->depth_C(to_region));
    from.object_id(from_region).copyTo(to->object_id(to_region));
  }
}

}  // namespace

FixedCameraRenderer::FixedCameraRenderer(const perception::CameraModel& camera,
                                         const Eigen::Isometry3d& T_WC)
    : camera_(camera.Clone()), T_WC_(T_WC), pinhole_(camera.model_name() == "pinhole") {}

bool FixedCameraRenderer::UpdateBackground(const Scene& scene, const RenderOptions& options) {
  const std::vector<SceneObject>& objects = scene.objects();
  const bool restart = background_.radiance.empty() || objects.size() != background_poses_.size() ||
                       options != background_options_;
  if (restart) moved_.assign(objects.size(), false);
  bool stale = restart;
  for (size_t i = 0; i < objects.size() && !restart; ++i) {
    if (!moved_[i] && !(objects[i].T_WO.matrix() == background_poses_[i].matrix())) {
      moved_[i] = true;
      stale = true;
    }
  }
  if (!stale) return false;
  // Moved objects wait behind the camera: no ray reaches them, no LED of theirs projects.
  Scene background = scene;
  Eigen::Isometry3d T_CO_parking = Eigen::Isometry3d::Identity();
  T_CO_parking.translation() = Eigen::Vector3d(0.0, 0.0, -1000.0);
  for (size_t i = 0; i < objects.size(); ++i) {
    if (moved_[i]) background.SetPose(objects[i].id, T_WC_ * T_CO_parking);
  }
  caster_.Render(background, *camera_, T_WC_, options, &background_);
  background_poses_.clear();
  for (const SceneObject& object : objects) background_poses_.push_back(object.T_WO);
  background_options_ = options;
  ++background_renders_;
  return true;
}

bool FixedCameraRenderer::MovedRegion(const Scene& scene, const RenderOptions& options,
                                      cv::Rect* region) const {
  const Eigen::Isometry3d T_CW = T_WC_.inverse();
  const std::vector<SceneObject>& objects = scene.objects();
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (!moved_[i]) continue;
    const SceneObject& object = objects[i];
    const double radius_m = BoundingRadius(object.primitive);
    if (!std::isfinite(radius_m)) return false;
    const Eigen::Vector3d c_C = T_CW * (object.T_WO * BoundingCenter(object.primitive));
    // The bounding cube (axes of C) must lie in front of the camera for its projection to hold.
    if (c_C.z() - radius_m <= 1e-3) return false;
    double ox0 = std::numeric_limits<double>::infinity(), oy0 = ox0, ox1 = -ox0, oy1 = -ox0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p_C =
          c_C +
          radius_m * Eigen::Vector3d(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
      Eigen::Vector2d px;
      if (!camera_->Project(p_C, &px)) return false;
      ox0 = std::min(ox0, px.x());
      ox1 = std::max(ox1, px.x());
      oy0 = std::min(oy0, px.y());
      oy1 = std::max(oy1, px.y());
    }
    double margin = kNeighbourMarginPx;
    if (std::holds_alternative<Led>(object.primitive)) {
      // sigma = max(min_led_sigma_px, half the projected emitter radius) <= these bounds.
      const double half_extent = 0.5 * std::max(ox1 - ox0, oy1 - oy0);
      margin += kLedWindowSigmas * std::max(options.min_led_sigma_px, half_extent) + 1.0;
    }
    x0 = std::min(x0, ox0 - margin);
    y0 = std::min(y0, oy0 - margin);
    x1 = std::max(x1, ox1 + margin);
    y1 = std::max(y1, oy1 + margin);
  }
  const cv::Rect image(0, 0, camera_->width(), camera_->height());
  if (!(x0 <= x1)) {
    *region = cv::Rect();  // nothing moved
    return true;
  }
  const auto clamp = [](double v, int lo, int hi) {
    return static_cast<int>(std::clamp(v, static_cast<double>(lo), static_cast<double>(hi)));
  };
  const int left = clamp(std::floor(x0), 0, image.width),
            top = clamp(std::floor(y0), 0, image.height);
  const int right = clamp(std::ceil(x1) + 1, 0, image.width);
  const int bottom = clamp(std::ceil(y1) + 1, 0, image.height);
  *region = cv::Rect(left, top, std::max(0, right - left), std::max(0, bottom - top));
  return true;
}

void FixedCameraRenderer::Render(const Scene& scene, const RenderOptions& options,
                                 RenderOutput* output) {
  const cv::Rect image(0, 0, camera_->width(), camera_->height());
  const auto full_render = [&] {
    caster_.Render(scene, *camera_, T_WC_, options, output);
    last_render_fraction_ = 1.0;
  };
  if (!pinhole_) return full_render();
  UpdateBackground(scene, options);
  cv::Rect core;
  if (!MovedRegion(scene, options, &core)) return full_render();
  const cv::Rect cast =
      cv::Rect(core.x - kNeighbourMarginPx, core.y - kNeighbourMarginPx,
               core.width + 2 * kNeighbourMarginPx, core.height + 2 * kNeighbourMarginPx) &
      image;
  if (core.area() > 0 && cast.area() > image.area() / 2) return full_render();
  output->radiance = background_.radiance.clone();
  output->depth_C = background_.depth_C.empty() ? cv::Mat() : background_.depth_C.clone();
  output->object_id = background_.object_id.empty() ? cv::Mat() : background_.object_id.clone();
  last_render_fraction_ = 0.0;
  if (core.area() == 0) return;
  // The full camera's rays for the pixels of `cast`: same focal lengths, principal point moved by
  // an integer (exact in floating point).
  const Eigen::Vector4d k = camera_->intrinsics();
  const perception::PinholeCamera crop(
      cast.width, cast.height,
      perception::PinholeIntrinsics{k(0), k(1), k(2) - cast.x, k(3) - cast.y});
  RenderOutput cropped;
  caster_.Render(scene, crop, T_WC_, options, &cropped);
  CopyRegion(cropped, core - cast.tl(), core, output);
  last_render_fraction_ = static_cast<double>(cast.area()) / image.area();
}

}  // namespace aperture::sim
