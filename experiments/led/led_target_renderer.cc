#include "experiments/led/led_target_renderer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sim/scene/textures.h"

namespace aperture::experiments {
namespace {

Eigen::Isometry3d AtPosition(const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = p;
  return T;
}

}  // namespace

LedTargetRenderer::LedTargetRenderer(const perception::LedConfiguration& configuration,
                                     std::shared_ptr<const perception::CameraModel> camera,
                                     const LedTargetRenderParams& params)
    : configuration_(configuration),
      camera_(std::move(camera)),
      params_(params),
      effects_(params.effects) {
  if (!camera_) throw std::invalid_argument("LedTargetRenderer: no camera model given");
  sim::Material ceiling;
  ceiling.texture = sim::MakeValueNoiseTexture(sim::ProceduralTextureParams{});
  scene_.AddObject({"ceiling", sim::Rectangle{{30.0, 30.0}, {}, {}}, ceiling,
                    AtPosition({0.0, 0.0, params_.ceiling_distance_m})});
  if (params_.body_size_m.minCoeff() > 0.0) {
    sim::Material body;
    body.color = sim::Rgb::Constant(0.2f);  // dark plastic and carbon
    scene_.AddObject({"body", sim::Box{params_.body_size_m}, body, Eigen::Isometry3d::Identity()});
  }
  for (int i = 0; i < configuration_.size(); ++i) {
    led_ids_.push_back(scene_.AddObject(
        {"led" + std::to_string(i),
         sim::Led{params_.led_radius_m, params_.led_intensity, sim::Rgb::Ones()},
         {},
         AtPosition(configuration_.p_T()[i])}));
  }
}

std::vector<int> LedTargetRenderer::OccludedLeds(const Eigen::Isometry3d& T_CT) const {
  const Eigen::Vector3d p_TC = T_CT.inverse().translation();
  std::vector<int> occluded;
  for (int i = 0; i < configuration_.size(); ++i) {
    const Eigen::Vector3d to_led = configuration_.p_T()[i] - p_TC;
    if (scene_.Intersect(p_TC, to_led, 0.0, to_led.norm() - params_.led_radius_m)) {
      occluded.push_back(i);
    }
  }
  return occluded;
}

cv::Mat LedTargetRenderer::Render(const std::function<Eigen::Isometry3d(double)>& T_CT_at,
                                  double t_s, int frame_index, const std::vector<int>& hidden) {
  // An occluded LED moves 1 km to -z_T, behind the camera (which looks along +z_T): never drawn.
  for (int i = 0; i < configuration_.size(); ++i) {
    const bool is_hidden = std::find(hidden.begin(), hidden.end(), i) != hidden.end();
    scene_.SetPose(led_ids_[i], AtPosition(is_hidden ? Eigen::Vector3d(0.0, 0.0, -1000.0)
                                                     : configuration_.p_T()[i]));
  }
  sim::RenderOptions options;
  options.ground_truth = false;
  options.min_led_sigma_px = params_.min_led_sigma_px;
  const sim::CapturedFrame captured = effects_.Capture(
      ray_caster_, scene_, *camera_, [&](double t) { return T_CT_at(t).inverse(); }, t_s,
      frame_index, options);
  return captured.frame.image;
}

}  // namespace aperture::experiments
