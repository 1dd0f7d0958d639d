#pragma once
// Where a rendered camera frame's CPU time goes, by the renderer's stages (ray_caster.h,
// camera_effects.h), in process CPU seconds (perception/cpu_time.h: the rows rendered by
// oneTBB's workers included):
//   setup_s          per-pixel ray table lookup, objects into the camera frame, per-tile culling
//   centers_s        one ray per pixel centre: traversal and shading (one pass, not separable
//                    without a timer per pixel); all k x k rays when supersampling is not adaptive
//   supersampling_s  adaptive supersampling: edge detection and the k x k rays of edge pixels
//   leds_s           LED blobs
//   blur_s           motion blur: copying and averaging the subframes
//   noise_s          shot / read noise, gain and 8-bit quantization
// A RenderProfileScope collects them on the thread that renders (RayCaster::Render and
// CameraEffects::Capture called on that thread) for its lifetime; without one the stage timers
// cost one branch. Scopes nest: the innermost collects, and the outer one resumes when it ends.
namespace aperture::sim {

struct RenderProfile {
  double setup_s = 0.0;
  double centers_s = 0.0;
  double supersampling_s = 0.0;
  double leds_s = 0.0;
  double blur_s = 0.0;
  double noise_s = 0.0;
  int renders = 0;  // RayCaster::Render calls (motion-blur subframes each count)

  double total_s() const {
    return setup_s + centers_s + supersampling_s + leds_s + blur_s + noise_s;
  }
};

class RenderProfileScope {
 public:
  explicit RenderProfileScope(RenderProfile* profile);
  ~RenderProfileScope();
  RenderProfileScope(const RenderProfileScope&) = delete;
  RenderProfileScope& operator=(const RenderProfileScope&) = delete;

  // The profile collecting on this thread, or nullptr.
  static RenderProfile* Current();

 private:
  RenderProfile* previous_;
};

// The current profile's `stage` field, or nullptr (for perception::ScopedCpuTimer):
// ScopedCpuTimer timer(RenderStage(&RenderProfile::centers_s));
double* RenderStage(double RenderProfile::*stage);

}  // namespace aperture::sim
