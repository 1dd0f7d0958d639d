#pragma once
// Renders an infrared-LED target for `aperture bench led` through the simulator: a sim::Scene with
// one sim::Led emitter per LED of the configuration (target frame T = world frame W), a dark
// textured ceiling behind the target, and the camera at T_WC = T_CT^-1, so the target's motion is
// the camera's and the exposure's motion blur applies (sim::CameraEffects, infrared mode: dark
// scene, bright LEDs, shot and read noise, 8-bit clipping). The ground truth of a frame is
// T_CT(t_s) at mid-exposure. With a body (body_size_m > 0), a dark box centred on T's origin
// hides the LEDs behind it as the ray caster does (an LED is drawn only when no surface lies
// between it and the camera); OccludedLeds gives the ground truth of which.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/led/led_configuration.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/scene.h"

namespace aperture::experiments {

// Calibration-level errors of the rendered world against the nominal camera and configuration
// the tracker is given (issue 21): the image is rendered with the intrinsics and LED positions
// off by these, the ground truth stays the nominal target frame T. Zero = renders match the
// tracker's model exactly.
struct LedCalibrationError {
  double focal_length_error = 0.0;  // fx, fy of the rendering camera = nominal * (1 + this)
  Eigen::Vector2d principal_point_error_px = Eigen::Vector2d::Zero();  // added to cx, cy
  // Every LED moved by this distance in a direction drawn per LED (seeded by `seed`) [m].
  double led_position_error_m = 0.0;
  std::uint64_t seed = 1;

  bool Any() const {
    return focal_length_error != 0.0 || !principal_point_error_px.isZero() ||
           led_position_error_m != 0.0;
  }
};

struct LedTargetRenderParams {
  double led_radius_m = 0.0025;  // SMD LED emitter (Harvatek HT-260, thesis C.4.1: ~2-3 mm)
  // Blob energy at 1 m [radiance * px^2]: ~3x full scale at the blob peak at 5.6 m, so the
  // farthest sweep distance is still detected above the 120 threshold; nearer LEDs saturate.
  double led_intensity = 150.0;
  double min_led_sigma_px = 0.8;  // lens blur of a point source (renderer floor)
  // sim::Led::radiation_exponent of every LED, whose axis faces -z_T (the camera's side of the
  // target; the ceiling is behind it at +z_T). 0: isotropic, 1: Lambertian.
  double led_radiation_exponent = 0.0;
  double ceiling_distance_m = 3.0;  // dark textured plane at z_T = +3 m behind the target
  // Edge lengths of the target's body, a box centred on T's origin [m]; zero = no body (the LEDs
  // are never occluded but by `hidden`).
  Eigen::Vector3d body_size_m = Eigen::Vector3d::Zero();
  sim::CameraEffectsParams effects = DefaultEffects();
  LedCalibrationError calibration_error;  // needs a PinholeCamera when any is set

  // mvBlueFOX-like sensor behind an IR-pass filter: read noise 1 % of full scale (~2.5 gray
  // levels), shot noise of a 4000 e- well, 2 ms exposure with motion blur over 3 subframes.
  static sim::CameraEffectsParams DefaultEffects() {
    sim::CameraEffectsParams effects;
    effects.infrared = true;
    effects.read_noise_sigma = 0.01;
    effects.full_well_electrons = 4000.0;
    effects.exposure_s = 0.002;
    effects.motion_blur_subframes = 3;
    return effects;
  }
};

class LedTargetRenderer {
 public:
  // Throws std::invalid_argument for a null camera, invalid effects parameters, or calibration
  // errors with a camera that is not a PinholeCamera.
  LedTargetRenderer(const perception::LedConfiguration& configuration,
                    std::shared_ptr<const perception::CameraModel> camera,
                    const LedTargetRenderParams& params = {});

  // The 8-bit image of the frame at mid-exposure time t_s (T_CT_at is sampled over the
  // exposure); `hidden` LEDs (indices into the configuration) are occluded. frame_index seeds
  // the sensor noise.
  cv::Mat Render(const std::function<Eigen::Isometry3d(double t_s)>& T_CT_at, double t_s,
                 int frame_index, const std::vector<int>& hidden = {});

  // The LEDs (indices into the configuration) the body hides from the camera at T_CT: a surface
  // between the camera and the LED's emitter.
  std::vector<int> OccludedLeds(const Eigen::Isometry3d& T_CT) const;

  // The nominal camera (the tracker's calibration).
  const perception::CameraModel& camera() const { return *camera_; }
  // What the image is rendered with: the nominal camera and configuration with
  // params.calibration_error applied.
  const perception::CameraModel& rendering_camera() const { return *rendering_camera_; }
  const perception::LedConfiguration& rendered_configuration() const { return configuration_; }

 private:
  perception::LedConfiguration configuration_;  // as rendered (with the LED position errors)
  std::shared_ptr<const perception::CameraModel> camera_;
  std::shared_ptr<const perception::CameraModel> rendering_camera_;
  LedTargetRenderParams params_;
  sim::CameraEffects effects_;
  sim::Scene scene_;
  std::vector<int> led_ids_;
  sim::RayCaster ray_caster_;
};

}  // namespace aperture::experiments
