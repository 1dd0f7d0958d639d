#pragma once
// Sensor effects on top of the ray caster's linear radiance, and frame capture with motion blur.
//   signal  = radiance averaged over the exposure (motion blur: `motion_blur_subframes` renders
//             at evenly spaced times over [t_mid - exposure/2, t_mid + exposure/2], the caller
//             provides T_WC(t)); 1.0 = full scale
//   noisy   = signal + N(0, signal / full_well_electrons) (shot noise, Gaussian approximation of
//             Poisson) + N(0, read_noise_sigma^2)
//   image   = clip(gain * noisy, 0, 1) * 255, rounded to CV_8UC1 (gray) / CV_8UC3 (BGR)
// Noise is a pure function of (seed, frame_index, pixel, channel): identical for any thread
// count, different between frames. Infrared mode renders with reflectance_scale =
// infrared_reflectance_scale (dark scene) while LEDs keep their radiance (emitters dominate).
// Ground truth (depth, ids) is the one of the subframe closest to t_mid (exact for odd counts).
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>

#include "perception/camera/camera_model.h"
#include "perception/sensor_data.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/scene.h"

namespace aperture::sim {

struct CameraEffectsParams {
  double gain = 1.0;                   // digital gain applied to the noisy signal
  double full_well_electrons = 0.0;    // shot noise: 1.0 signal = this many electrons; 0 = off
  double read_noise_sigma = 0.0;       // read noise std dev [fraction of full scale]; 0 = off
  std::uint64_t seed = 1;
  double exposure_s = 0.0;             // exposure time for motion blur [s]
  int motion_blur_subframes = 1;       // renders averaged over the exposure (1 = no blur)
  bool infrared = false;               // IR mode: dark scene, bright LEDs
  float infrared_reflectance_scale = 0.03f;  // surface/sky radiance factor in IR mode
};

// A captured frame: the 8-bit image (in perception::Frame, as a real camera delivers it) plus
// the simulator's ground truth.
struct CapturedFrame {
  perception::Frame frame;
  cv::Mat radiance;   // linear signal before noise (CV_32FC1 / CV_32FC3)
  cv::Mat depth_C;    // CV_32FC1 z_C [m], +inf sky
  cv::Mat object_id;  // CV_32SC1, 0 sky
};

class CameraEffects {
 public:
  // Throws std::invalid_argument naming the field for gain <= 0, negative noise or exposure,
  // or motion_blur_subframes < 1.
  explicit CameraEffects(const CameraEffectsParams& params);

  // Renders the frame at mid-exposure time t_mid_s with motion blur, applies noise and gain.
  // options.reflectance_scale is overridden in infrared mode.
  CapturedFrame Capture(RayCaster& ray_caster, const Scene& scene,
                        const perception::CameraModel& camera,
                        const std::function<Eigen::Isometry3d(double t_s)>& T_WC_at,
                        double t_mid_s, int frame_index, const RenderOptions& options = {}) const;

  // The same with any renderer in place of RayCaster::Render (e.g. sim/sitl/
  // fixed_camera_renderer.h): render(T_WC, options, output) fills *output like RayCaster::Render.
  using RenderFunction =
      std::function<void(const Eigen::Isometry3d& T_WC, const RenderOptions&, RenderOutput*)>;
  CapturedFrame Capture(const RenderFunction& render,
                        const std::function<Eigen::Isometry3d(double t_s)>& T_WC_at, double t_mid_s,
                        int frame_index, const RenderOptions& options = {}) const;

  // Noise + gain + quantization of a linear radiance image (CV_32FC1 or CV_32FC3).
  cv::Mat ToImage8U(const cv::Mat& radiance, int frame_index) const;

  const CameraEffectsParams& params() const { return params_; }

 private:
  CameraEffectsParams params_;
};

}  // namespace aperture::sim
