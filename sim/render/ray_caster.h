#pragma once
// CPU ray-casting renderer. For a camera model (perception/camera/camera_model.h; any model, e.g.
// a 180 deg fisheye, since each pixel's ray is CameraModel::Unproject) and a camera pose T_WC it
// renders the scene's linear radiance plus per-pixel ground truth:
//   radiance   CV_32FC1 (luminance 0.299 R + 0.587 G + 0.114 B) or CV_32FC3 (BGR), linear,
//              1.0 = white albedo under full light; LEDs may exceed 1 (the sensor clips).
//   depth_C    CV_32FC1, z_C of the surface seen through the pixel centre [m]; +inf for sky.
//   object_id  CV_32SC1, Scene object id through the pixel centre (LEDs: within 2 sigma of the
//              blob centre), 0 for sky.
// Shading: Lambertian, Scene::lighting (ambient + one directional light, no shadows); sky from
// Scene::sky. Textures are sampled at the mip level matching each sample's footprint on the
// surface (distance * angular sample size / sqrt(cos incidence)). With supersampling k, each
// pixel averages k x k rays, one per cell of a k x k sub-pixel grid with all x and all y offsets
// distinct (box filter; ground truth stays on the pixel centre ray).
// Adaptive supersampling (default): every pixel centre is traced first; a pixel gets its k x k
// rays only where it or one of its 8 neighbours differs at the centre: another object (or sky),
// a surface normal turned by more than ~8 deg (box edges), or, on hard-edged textures
// (Texture::has_hard_edges: checkerboard, nearest-filtered tags and gap patterns), an albedo
// luminance step > 0.02. Any straight edge crossing a pixel separates its centre from one of the
// 8 neighbour centres, so every pixel an edge touches is supersampled exactly as without
// adaptivity; elsewhere the centre sample stands for the pixel (its texture mip level chosen for
// the whole pixel's footprint). Features thinner than a pixel that no centre hits are missed.
//
// LEDs (Led primitives) are drawn as an isotropic Gaussian radiance distribution centred on the
// projected emitter centre, integrated exactly over each pixel's square footprint (erf
// differences: the limit of infinite supersampling), so the blob's intensity-weighted centroid
// is the projected centre (bias ~exp(-2 pi^2 sigma^2) px, < 1e-3 px for sigma >= 0.6 px).
// sigma = max(min_led_sigma_px, half the projected emitter radius); energy = intensity / d^2
// (d: camera-emitter distance [m]). An LED is drawn when its centre projects and no surface is
// between camera and emitter.
//
// Speed: per-pixel rays are computed once per camera (cached, keyed by the model's name, size
// and a fingerprint of its rays), per frame each object gets its transform into the camera frame
// and a bounding sphere, and every 16 x 16 pixel tile a list of the objects its cone of rays
// can reach (bounding sphere in the cone, plane in front), sorted by a lower bound on their
// distance over the cone; a ray stops at the first candidate whose bound is not nearer than its
// hit so far. Rows run in parallel (oneTBB) and each row first tries the object hit by its
// previous pixel. Output is independent of the thread count (rows are independent).
// A RayCaster is not safe for concurrent Render calls (the ray cache); use one per thread.
//
// Back ends of the ray-object step (RayBackend): kTileCulling is the search above; kEmbree puts
// each frame's objects into an Intel Embree 3 BVH (embree_scene.h) and shades its hits with the
// same code. The two give the same images up to rays grazing an edge (tests/sim/
// render_backend_test.cc); docs/results/speed.md compares their speed.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"
#include "sim/scene/scene.h"

namespace aperture::sim {

struct RenderOptions {
  bool color = false;     // false: gray CV_32FC1; true: BGR CV_32FC3
  int supersampling = 1;  // k >= 1: k x k rays per pixel (2-3 for sub-pixel-accurate edges)
  // true: k x k rays only for pixels at edges (see above), ~1.3x the cost of k = 1 instead of k^2.
  bool adaptive_supersampling = true;
  bool ground_truth = true;  // fill depth_C and object_id
  // Multiplies surface and sky radiance, not LEDs: < 1 for infrared mode (dark scene, bright
  // emitters; camera_effects.h).
  float reflectance_scale = 1.0f;
  double min_led_sigma_px = 0.6;  // floor of the LED blob sigma (optics blur of a point source)
};

// Field-by-field equality (renderers that cache output per option set compare with it).
bool operator==(const RenderOptions& a, const RenderOptions& b);
inline bool operator!=(const RenderOptions& a, const RenderOptions& b) { return !(a == b); }

// An LED's blob is drawn over +-kLedWindowSigmas sigma around its projection.
constexpr double kLedWindowSigmas = 4.5;

struct RenderOutput {
  cv::Mat radiance;
  cv::Mat depth_C;
  cv::Mat object_id;
};

enum class RayBackend { kTileCulling, kEmbree };

class EmbreeScene;

class RayCaster {
 public:
  // Throws std::runtime_error for kEmbree in a build without Embree (EmbreeAvailable()).
  explicit RayCaster(RayBackend backend = RayBackend::kTileCulling);
  ~RayCaster();

  // Renders into *output (buffers reused when their size and type match). Throws
  // std::invalid_argument for supersampling < 1 or a non-finite T_WC.
  void Render(const Scene& scene, const perception::CameraModel& camera,
              const Eigen::Isometry3d& T_WC, const RenderOptions& options, RenderOutput* output);
  RenderOutput Render(const Scene& scene, const perception::CameraModel& camera,
                      const Eigen::Isometry3d& T_WC, const RenderOptions& options = {});

 private:
  struct RayTable;
  struct CenterSample;
  struct PixelPass;
  const RayTable& Rays(const perception::CameraModel& camera, int supersampling);
  // Render's pixel steps (ray_caster.cc): centre rays, then adaptive supersampling at edges.
  void ShadePixelCenters(const PixelPass& pass, int h, bool adaptive);
  void SupersampleEdges(const PixelPass& pass, int h);

  std::unique_ptr<EmbreeScene> embree_;               // set for RayBackend::kEmbree
  std::vector<std::unique_ptr<RayTable>> ray_cache_;  // most recently used last
  // Adaptive supersampling, per pixel: centre samples and edge bits towards 4 neighbours.
  std::vector<CenterSample> center_samples_;
  std::vector<std::uint8_t> edge_pairs_;
};

}  // namespace aperture::sim
