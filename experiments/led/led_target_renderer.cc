#include "experiments/led/led_target_renderer.h"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>

#include "perception/camera/pinhole_camera.h"
#include "sim/scene/textures.h"

namespace aperture::experiments {
namespace {

Eigen::Isometry3d AtPosition(const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = p;
  return T;
}

// An emitter at p whose axis +z_O is -z_T (half a turn about x_T).
Eigen::Isometry3d FacingMinusZ(const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = AtPosition(p);
  T.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return T;
}

// The configuration with every LED moved by error.led_position_error_m in a random direction.
perception::LedConfiguration DisplacedConfiguration(
    const perception::LedConfiguration& configuration, const LedCalibrationError& error) {
  if (error.led_position_error_m == 0.0) return configuration;
  std::mt19937_64 rng(error.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> p_T = configuration.p_T();
  for (Eigen::Vector3d& p : p_T) {
    const Eigen::Vector3d direction(normal(rng), normal(rng), normal(rng));
    p += error.led_position_error_m * direction.normalized();
  }
  return perception::LedConfiguration(p_T, configuration.source() + " (LEDs displaced)");
}

// The camera with error's intrinsics errors; the camera itself when there are none.
std::shared_ptr<const perception::CameraModel> RenderingCamera(
    std::shared_ptr<const perception::CameraModel> camera, const LedCalibrationError& error) {
  if (!camera) throw std::invalid_argument("LedTargetRenderer: no camera model given");
  if (error.focal_length_error == 0.0 && error.principal_point_error_px.isZero()) return camera;
  if (!dynamic_cast<const perception::PinholeCamera*>(camera.get())) {
    throw std::invalid_argument(
        "LedTargetRenderer: intrinsics errors (calibration_error) need a PinholeCamera; set "
        "focal_length_error and principal_point_error_px to 0 for other camera models");
  }
  perception::PinholeIntrinsics k = perception::PinholeIntrinsics::FromVector(camera->intrinsics());
  k.fx *= 1.0 + error.focal_length_error;
  k.fy *= 1.0 + error.focal_length_error;
  k.cx += error.principal_point_error_px.x();
  k.cy += error.principal_point_error_px.y();
  return std::make_shared<perception::PinholeCamera>(camera->width(), camera->height(), k);
}

}  // namespace

LedTargetRenderer::LedTargetRenderer(const perception::LedConfiguration& configuration,
                                     std::shared_ptr<const perception::CameraModel> camera,
                                     const LedTargetRenderParams& params)
    : configuration_(DisplacedConfiguration(configuration, params.calibration_error)),
      camera_(std::move(camera)),
      rendering_camera_(RenderingCamera(camera_, params.calibration_error)),
      params_(params),
      effects_(params.effects) {
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
    led_ids_.push_back(scene_.AddObject({"led" + std::to_string(i),
                                         sim::Led{params_.led_radius_m, params_.led_intensity,
                                                  sim::Rgb::Ones(), params_.led_radiation_exponent},
                                         {},
                                         FacingMinusZ(configuration_.p_T()[i])}));
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
    scene_.SetPose(led_ids_[i], FacingMinusZ(is_hidden ? Eigen::Vector3d(0.0, 0.0, -1000.0)
                                                       : configuration_.p_T()[i]));
  }
  sim::RenderOptions options;
  options.ground_truth = false;
  options.min_led_sigma_px = params_.min_led_sigma_px;
  const sim::CapturedFrame captured = effects_.Capture(
      ray_caster_, scene_, *rendering_camera_, [&](double t) { return T_CT_at(t).inverse(); }, t_s,
      frame_index, options);
  return captured.frame.image;
}

}  // namespace aperture::experiments
