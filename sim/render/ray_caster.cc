#include "sim/render/ray_caster.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "control/constants.h"
#include "perception/cpu_time.h"
#include "sim/render/embree_scene.h"
#include "sim/render/ray_trace.h"
#include "sim/render/render_profile.h"

namespace aperture::sim {
namespace {

using control::kInf;
constexpr size_t kMaxCachedCameras = 4;
// LED blob: ground-truth mask radius in sigmas (the window: kLedWindowSigmas, ray_caster.h).
constexpr double kLedMaskSigmas = 2.0;
// Adaptive supersampling: neighbouring centre samples on one object differ at an edge when their
// normals turn by more than acos(0.99) = 8.1 deg (box edges; a 0.5 m sphere 3 m away turns by
// ~1.6 deg per fisheye pixel) or, on hard-edged textures, the albedo luminance steps by more than
// 0.02 (~5 grey levels; pattern edges step by ~0.9).
constexpr float kEdgeNormalCos = 0.99f;
constexpr float kEdgeLuminanceStep = 0.02f;
// Pixels per side of the image tiles whose rays share one candidate-object list per frame.
constexpr int kTileSize = 16;
// Widening of each tile's ray cone [rad]: covers the float rounding of the stored rays.
constexpr double kTileConeMargin_rad = 1e-5;
// Relative shrink of each tile's lower bounds on the hit distance: covers the stored rays' norm
// (float rounding, |d| = 1 +- 1e-7, and t is in units of |d|) and the rounding of the bound.
constexpr double kTileLowerDistanceRelative = 1e-6;
// Sub-pixel rays handed to the Embree back end at once (EmbreeScene::NearestN).
constexpr int kEmbreeBatch = 16;

float Luminance(const Rgb& c) { return 0.299f * c.x() + 0.587f * c.y() + 0.114f * c.z(); }

// sample_angle_rad: angular size of the sample (pixel angle / supersampling) for the texture
// footprint: distance * angle, stretched by 1 / sqrt(cos incidence) (geometric mean of the
// footprint's two axes). *albedo (optional) receives the surface albedo (sky: its radiance).
Rgb Shade(const Scene& scene, const FrameContext& frame, const Eigen::Vector3d& d_C,
          const RayHit& ray_hit, double sample_angle_rad, Rgb* albedo = nullptr) {
  if (ray_hit.index < 0) {
    const Rgb sky = scene.sky.Radiance(frame.R_WC * d_C);
    if (albedo) *albedo = sky;
    return sky;
  }
  const FrameObject& f = frame.objects[static_cast<size_t>(ray_hit.index)];
  const LocalHit& hit = ray_hit.local;
  Eigen::Vector3d n_O = hit.n_O;
  double cos_incidence = n_O.dot(ray_hit.d_O);
  if (cos_incidence > 0.0) {
    n_O = -n_O;  // two-sided: the side facing the camera
  } else {
    cos_incidence = -cos_incidence;
  }
  const float lambert = static_cast<float>(std::max(0.0, n_O.dot(f.to_light_O)));
  const double footprint_m = hit.t_m * sample_angle_rad / std::sqrt(std::max(cos_incidence, 1e-3));
  const Rgb surface_albedo = f.material->Albedo(hit.uv_m, footprint_m);
  if (albedo) *albedo = surface_albedo;
  return surface_albedo * (scene.lighting.ambient + scene.lighting.directional * lambert);
}

// Mass of N(mu, sigma^2) in [i - 0.5, i + 0.5] for i = first .. first + n - 1.
std::vector<double> PixelIntegrals(double mu, double sigma, int first, int n) {
  std::vector<double> w(static_cast<size_t>(n));
  const double k = 1.0 / (std::sqrt(2.0) * sigma);
  for (int j = 0; j < n; ++j) {
    const double x = first + j;
    w[static_cast<size_t>(j)] = 0.5 * (std::erf((x + 0.5 - mu) * k) - std::erf((x - 0.5 - mu) * k));
  }
  return w;
}

Eigen::Vector3d AnyPerpendicular(const Eigen::Vector3d& v) {
  const Eigen::Vector3d a =
      std::abs(v.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return v.cross(a).normalized();
}

}  // namespace

// Unit rays in C for every pixel centre and (supersampling > 1) every sub-pixel sample.
struct RayCaster::RayTable {
  std::string model_name;
  int width = 0;
  int height = 0;
  int supersampling = 1;
  std::array<Eigen::Vector3d, 5> fingerprint;
  std::vector<Eigen::Vector3f> center;  // width * height
  std::vector<Eigen::Vector3f> sub;     // width * height * k * k (empty for k = 1)
  std::vector<float> pixel_angle_rad;   // angular pixel size (to the right / lower neighbour)
  // Per kTileSize x kTileSize tile (row-major): the cone around all its rays (centre and sub).
  int tiles_x = 0;
  int tiles_y = 0;
  std::vector<Eigen::Vector3d> tile_axis;
  std::vector<double> tile_half_angle_rad;

  size_t Tile(int x, int y) const {
    return static_cast<size_t>(y / kTileSize) * tiles_x + static_cast<size_t>(x / kTileSize);
  }
};

namespace {

// A tile's cone of rays: unit axis and the cosine and sine of its half angle.
struct RayCone {
  Eigen::Vector3d axis_C;
  double cos_half;
  double sin_half;
};

// For rays within the cone: std::nullopt when none can hit the frame object (its bounding
// sphere outside the cone, or a plane only behind), else a lower bound on the hit distance t
// (bounding sphere: |centre| - radius; plane: |offset| over the largest cosine between the
// cone's rays and the normal facing the plane). Angles are compared through their cosines
// (cos(a +- b) expanded), no inverse trigonometry. Conservative: when unsure, a hit is possible
// and the bound is lower. Valid for any half angle below 180 deg.
std::optional<double> ConeLowerDistance(const FrameObject& f, const RayCone& cone) {
  double t_lower = 0.0;
  if (f.bounded) {
    const double distance = std::sqrt(f.center_sq);
    if (distance > f.radius) {
      // Outside when the angle to the centre exceeds half angle + the sphere's angular radius.
      const double sin_radius = f.radius / distance;
      const double cos_radius = std::sqrt(1.0 - sin_radius * sin_radius);
      const double sin_sum = cone.sin_half * cos_radius + cone.cos_half * sin_radius;
      const double cos_sum = cone.cos_half * cos_radius - cone.sin_half * sin_radius;
      const double cos_center = cone.axis_C.dot(f.center_C) / distance;
      if (sin_sum > 0.0 && cos_center < cos_sum) return std::nullopt;
      t_lower = distance - f.radius;
    }
  }
  if (f.planar && f.plane_offset_m != 0.0) {
    // t = offset / n.d > 0 needs n.d of the offset's sign: the angle between the cone's rays
    // and the normal facing the plane (n for offset > 0, -n for offset < 0) below 90 deg.
    const double cos_facing = std::clamp(
        std::copysign(1.0, f.plane_offset_m) * cone.axis_C.dot(f.n_C) / f.n_C.norm(), -1.0, 1.0);
    // Largest cosine over the cone: 1 when the facing normal is inside it, else the cosine of
    // (facing angle - half angle).
    const double cos_closest =
        cos_facing >= cone.cos_half
            ? 1.0
            : cos_facing * cone.cos_half + std::sqrt(1.0 - cos_facing * cos_facing) * cone.sin_half;
    if (cos_closest <= 0.0) return std::nullopt;
    t_lower = std::max(t_lower, std::abs(f.plane_offset_m) / cos_closest);
  }
  return t_lower * (1.0 - kTileLowerDistanceRelative);
}

}  // namespace

// What adaptive supersampling compares between neighbouring pixel centres.
struct RayCaster::CenterSample {
  int index;        // frame object index, -1 for sky
  bool hard_edged;  // the object's texture has hard edges
  float albedo_luminance;
  Eigen::Vector3f n_O;  // surface normal as hit, in the object frame

  // True when an edge lies between this and a neighbouring centre sample (thresholds above).
  bool EdgeTo(const CenterSample& other) const {
    if (index != other.index) return true;
    if (index < 0) return false;  // sky varies smoothly
    if (n_O.dot(other.n_O) < kEdgeNormalCos) return true;
    return hard_edged && std::abs(albedo_luminance - other.albedo_luminance) > kEdgeLuminanceStep;
  }
};

namespace {

std::array<Eigen::Vector3d, 5> Fingerprint(const perception::CameraModel& camera) {
  const double w = camera.width() - 1.0;
  const double h = camera.height() - 1.0;
  return {camera.Unproject({0.0, 0.0}), camera.Unproject({w, 0.0}), camera.Unproject({0.0, h}),
          camera.Unproject({w, h}), camera.Unproject({0.37 * w, 0.61 * h})};
}

}  // namespace

bool operator==(const RenderOptions& a, const RenderOptions& b) {
  return a.color == b.color && a.supersampling == b.supersampling &&
         a.adaptive_supersampling == b.adaptive_supersampling && a.ground_truth == b.ground_truth &&
         a.reflectance_scale == b.reflectance_scale && a.min_led_sigma_px == b.min_led_sigma_px;
}

RayCaster::RayCaster(RayBackend backend) {
  if (backend == RayBackend::kEmbree) embree_ = std::make_unique<EmbreeScene>();
}
RayCaster::~RayCaster() = default;

const RayCaster::RayTable& RayCaster::Rays(const perception::CameraModel& camera,
                                           int supersampling) {
  const auto fingerprint = Fingerprint(camera);
  for (size_t i = 0; i < ray_cache_.size(); ++i) {
    const RayTable& t = *ray_cache_[i];
    if (t.width == camera.width() && t.height == camera.height() &&
        t.supersampling == supersampling && t.model_name == camera.model_name() &&
        t.fingerprint == fingerprint) {
      std::rotate(ray_cache_.begin() + static_cast<long>(i),
                  ray_cache_.begin() + static_cast<long>(i) + 1, ray_cache_.end());
      return *ray_cache_.back();
    }
  }
  auto table = std::make_unique<RayTable>();
  table->model_name = camera.model_name();
  table->width = camera.width();
  table->height = camera.height();
  table->supersampling = supersampling;
  table->fingerprint = fingerprint;
  const int w = camera.width();
  const int k = supersampling;
  table->center.resize(static_cast<size_t>(w) * camera.height());
  if (k > 1) table->sub.resize(table->center.size() * static_cast<size_t>(k * k));
  tbb::parallel_for(
      tbb::blocked_range<int>(0, camera.height()), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          for (int x = 0; x < w; ++x) {
            const size_t p = static_cast<size_t>(y) * w + x;
            table->center[p] = camera.Unproject({double(x), double(y)}).normalized().cast<float>();
            for (int sy = 0; sy < k && k > 1; ++sy) {
              for (int sx = 0; sx < k; ++sx) {
                // One sample per cell of a k x k grid, shifted inside its cell so that all k^2
                // samples have distinct x and distinct y offsets (n-rooks within strata): edge
                // coverage of near-axis-aligned edges is then quantized in k^2 steps, not k.
                const double ox = (sx * k + sy + 0.5) / (k * k);
                const double oy = (sy * k + sx + 0.5) / (k * k);
                const Eigen::Vector2d px(x - 0.5 + ox, y - 0.5 + oy);
                table->sub[p * k * k + static_cast<size_t>(sy * k + sx)] =
                    camera.Unproject(px).normalized().cast<float>();
              }
            }
          }
        }
      });
  table->pixel_angle_rad.resize(table->center.size());
  const int h = camera.height();
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    auto angle = [&](size_t a, size_t b) {
      const Eigen::Vector3d u = table->center[a].cast<double>();
      const Eigen::Vector3d v = table->center[b].cast<double>();
      return std::atan2(u.cross(v).norm(), u.dot(v));
    };
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        const size_t horizontal = x + 1 < w ? p + 1 : p - 1;
        const size_t vertical = y + 1 < h ? p + w : p - w;
        table->pixel_angle_rad[p] = static_cast<float>(
            std::max(w > 1 ? angle(p, horizontal) : 0.0, h > 1 ? angle(p, vertical) : 0.0));
      }
    }
  });
  table->tiles_x = (w + kTileSize - 1) / kTileSize;
  table->tiles_y = (h + kTileSize - 1) / kTileSize;
  const size_t tiles = static_cast<size_t>(table->tiles_x) * table->tiles_y;
  table->tile_axis.assign(tiles, Eigen::Vector3d::Zero());
  table->tile_half_angle_rad.assign(tiles, 0.0);
  const size_t samples = static_cast<size_t>(k) * k;
  const auto for_each_ray = [&](int x, int y, const auto& visit) {
    const size_t p = static_cast<size_t>(y) * w + x;
    visit(table->center[p].cast<double>());
    for (size_t s = 0; s < table->sub.size() / table->center.size(); ++s) {
      visit(table->sub[p * samples + s].cast<double>());
    }
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for_each_ray(x, y,
                   [&](const Eigen::Vector3d& d) { table->tile_axis[table->Tile(x, y)] += d; });
    }
  }
  for (Eigen::Vector3d& axis : table->tile_axis) axis.normalize();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t t = table->Tile(x, y);
      for_each_ray(x, y, [&](const Eigen::Vector3d& d) {
        const double angle =
            std::acos(std::clamp(table->tile_axis[t].dot(d) / d.norm(), -1.0, 1.0));
        table->tile_half_angle_rad[t] = std::max(table->tile_half_angle_rad[t], angle);
      });
    }
  }
  for (double& half_angle : table->tile_half_angle_rad) half_angle += kTileConeMargin_rad;
  if (ray_cache_.size() >= kMaxCachedCameras) ray_cache_.erase(ray_cache_.begin());
  ray_cache_.push_back(std::move(table));
  return *ray_cache_.back();
}

RenderOutput RayCaster::Render(const Scene& scene, const perception::CameraModel& camera,
                               const Eigen::Isometry3d& T_WC, const RenderOptions& options) {
  RenderOutput output;
  Render(scene, camera, T_WC, options, &output);
  return output;
}

namespace {

// Render step 1: the non-LED objects in the camera frame C (FrameContext::objects, all_objects);
// LEDs go to *leds, they are splatted, not ray traced.
FrameContext PrepareFrameObjects(const Scene& scene, const Eigen::Isometry3d& T_WC,
                                 std::vector<const SceneObject*>* leds) {
  FrameContext frame;
  frame.R_WC = T_WC.linear();
  const Eigen::Vector3d to_light_W = -scene.lighting.direction_W.normalized();
  for (const SceneObject& object : scene.objects()) {
    if (std::holds_alternative<Led>(object.primitive)) {
      leds->push_back(&object);
      continue;
    }
    FrameObject f;
    f.primitive = &object.primitive;
    f.material = &object.material;
    f.id = object.id;
    const Eigen::Isometry3d T_OC = object.T_WO.inverse() * T_WC;
    f.R_OC = T_OC.linear();
    f.p_OC = T_OC.translation();
    f.to_light_O = object.T_WO.linear().transpose() * to_light_W;
    f.hard_edged = object.material.texture && object.material.texture->has_hard_edges();
    f.planar = std::holds_alternative<Rectangle>(object.primitive) ||
               std::holds_alternative<GroundPlane>(object.primitive);
    f.n_C = f.R_OC.row(2).transpose();
    f.plane_offset_m = -f.p_OC.z();  // n_C . p_CO with p_CO = -R_CO p_OC
    f.radius = BoundingRadius(object.primitive);
    f.bounded = std::isfinite(f.radius);
    f.center_C = T_WC.inverse() * (object.T_WO * BoundingCenter(object.primitive));
    f.center_sq = f.center_C.squaredNorm();
    f.radius_sq = f.radius * f.radius;
    frame.objects.push_back(f);
  }
  for (int i = 0; i < static_cast<int>(frame.objects.size()); ++i) {
    frame.all_objects.push_back({i, 0.0});
  }
  return frame;
}

// Render step 2: per image tile (cone tile_axis[t], half angle tile_half_angle_rad[t]) the objects
// its rays can hit, nearest lower bound first (FrameContext::tile_candidates, tile_begin).
void CullObjectsPerTile(const std::vector<Eigen::Vector3d>& tile_axis,
                        const std::vector<double>& tile_half_angle_rad, FrameContext* frame) {
  const size_t tiles = tile_axis.size();
  frame->tile_begin.reserve(tiles + 1);
  frame->tile_begin.push_back(0);
  for (size_t t = 0; t < tiles; ++t) {
    const RayCone cone{tile_axis[t], std::cos(tile_half_angle_rad[t]),
                       std::sin(tile_half_angle_rad[t])};
    for (int i = 0; i < static_cast<int>(frame->objects.size()); ++i) {
      if (const std::optional<double> t_lower =
              ConeLowerDistance(frame->objects[static_cast<size_t>(i)], cone)) {
        frame->tile_candidates.push_back({i, *t_lower});
      }
    }
    // Nearest first (ties by index, so the order is deterministic).
    std::sort(
        frame->tile_candidates.begin() + static_cast<std::ptrdiff_t>(frame->tile_begin.back()),
        frame->tile_candidates.end(), [](const TileCandidate& a, const TileCandidate& b) {
          return a.t_lower_m != b.t_lower_m ? a.t_lower_m < b.t_lower_m : a.index < b.index;
        });
    frame->tile_begin.push_back(frame->tile_candidates.size());
  }
}

using CandidateRange = std::pair<const TileCandidate*, const TileCandidate*>;

// Candidate objects of tile t for TraceRay (none with Embree, which does not use them).
CandidateRange TileCandidates(const FrameContext& frame, size_t t) {
  return frame.embree ? CandidateRange{} : frame.Candidates(t);
}

// Nearest hit along the unit ray d_C with t < t_max, from the frame's back end: the Embree BVH,
// or TraceRay over *candidates (nullptr: every object) trying `hint` first.
RayHit NearestHit(const FrameContext& frame, const Eigen::Vector3d& d_C,
                  const CandidateRange* candidates, int hint, double t_max) {
  if (frame.embree) return frame.embree->Nearest(d_C, t_max);
  if (candidates) return TraceRay(d_C, frame.objects, *candidates, hint, t_max);
  const CandidateRange all(frame.all_objects.data(),
                           frame.all_objects.data() + frame.all_objects.size());
  return TraceRay(d_C, frame.objects, all, hint, t_max);
}

// Render step 5: LEDs as exact pixel integrals of an isotropic Gaussian around the projected
// centre, with the emitter's radiation pattern, added to the radiance (and the ground truth within
// kLedMaskSigmas), unless occluded.
void SplatLeds(const std::vector<const SceneObject*>& leds, const FrameContext& frame,
               const perception::CameraModel& camera, const Eigen::Isometry3d& T_WC,
               const RenderOptions& options, RenderOutput* output) {
  const int w = camera.width();
  const int h = camera.height();
  const Eigen::Isometry3d T_CW = T_WC.inverse();
  for (const SceneObject* led_object : leds) {
    const Led& led = std::get<Led>(led_object->primitive);
    const Eigen::Vector3d p_C = T_CW * led_object->T_WO.translation();
    Eigen::Vector2d px;
    if (!camera.Project(p_C, &px)) continue;
    const double distance = p_C.norm();
    if (!(distance > led.radius_m)) continue;  // camera inside the emitter
    if (NearestHit(frame, p_C / distance, nullptr, -1, distance - led.radius_m).index >= 0) {
      continue;
    }
    double projected_radius_px = 0.0;
    const Eigen::Vector3d e1 = AnyPerpendicular(p_C);
    const Eigen::Vector3d e2 = p_C.normalized().cross(e1);
    int projected = 0;
    for (const Eigen::Vector3d& e : {e1, e2}) {
      Eigen::Vector2d px_edge;
      if (camera.Project(p_C + led.radius_m * e, &px_edge)) {
        projected_radius_px += (px_edge - px).norm();
        ++projected;
      }
    }
    if (projected > 0) projected_radius_px /= projected;
    const double sigma = std::max(options.min_led_sigma_px, 0.5 * projected_radius_px);
    double energy = led.intensity / (distance * distance);
    if (led.radiation_exponent > 0.0) {
      const Eigen::Vector3d axis_C = T_CW.linear() * led_object->T_WO.linear().col(2);
      const double cos_off_axis = -axis_C.dot(p_C) / distance;
      if (cos_off_axis <= 0.0) continue;  // behind the emitter's plane
      energy *= std::pow(cos_off_axis, led.radiation_exponent);
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(px.x() - kLedWindowSigmas * sigma)));
    const int x1 = std::min(w - 1, static_cast<int>(std::ceil(px.x() + kLedWindowSigmas * sigma)));
    const int y0 = std::max(0, static_cast<int>(std::floor(px.y() - kLedWindowSigmas * sigma)));
    const int y1 = std::min(h - 1, static_cast<int>(std::ceil(px.y() + kLedWindowSigmas * sigma)));
    if (x0 > x1 || y0 > y1) continue;
    const std::vector<double> wx = PixelIntegrals(px.x(), sigma, x0, x1 - x0 + 1);
    const std::vector<double> wy = PixelIntegrals(px.y(), sigma, y0, y1 - y0 + 1);
    const float gray_value = Luminance(led.color);
    const float depth_led = static_cast<float>(p_C.z());
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const float e = static_cast<float>(energy * wx[static_cast<size_t>(x - x0)] *
                                           wy[static_cast<size_t>(y - y0)]);
        if (options.color) {
          output->radiance.at<cv::Vec3f>(y, x) +=
              cv::Vec3f(e * led.color.z(), e * led.color.y(), e * led.color.x());
        } else {
          output->radiance.at<float>(y, x) += e * gray_value;
        }
        if (options.ground_truth && std::hypot(x - px.x(), y - px.y()) <= kLedMaskSigmas * sigma &&
            depth_led < output->depth_C.at<float>(y, x)) {
          output->depth_C.at<float>(y, x) = depth_led;
          output->object_id.at<int32_t>(y, x) = led_object->id;
        }
      }
    }
  }
}

}  // namespace

// One frame's pixel shading, shared by the centre pass and the adaptive edge pass.
struct RayCaster::PixelPass {
  const Scene& scene;
  const FrameContext& frame;
  const RayTable& rays;
  const RenderOptions& options;
  RenderOutput* output;
  int w;
  int k;  // supersampling
  float inv_samples;

  // Average radiance of the k x k sub-pixel rays of pixel (x, y); `hint` is tried first.
  Rgb Supersample(int x, int y, int hint) const {
    const size_t p = static_cast<size_t>(y) * w + x;
    const auto candidates = TileCandidates(frame, rays.Tile(x, y));
    const double sample_angle = rays.pixel_angle_rad[p] / k;
    const Eigen::Vector3f* sub = &rays.sub[p * k * k];
    Rgb sum = Rgb::Zero();
    if (frame.embree) {  // in packets of up to kEmbreeBatch rays
      std::array<RayHit, kEmbreeBatch> hits;
      for (int first = 0; first < k * k; first += kEmbreeBatch) {
        const int n = std::min(kEmbreeBatch, k * k - first);
        frame.embree->NearestN(sub + first, n, hits.data());
        for (int s = 0; s < n; ++s) {
          sum += Shade(scene, frame, sub[first + s].cast<double>(), hits[s], sample_angle);
        }
      }
      return Rgb(sum * inv_samples);
    }
    for (int s = 0; s < k * k; ++s) {
      const Eigen::Vector3d d = sub[s].cast<double>();
      const RayHit hit = NearestHit(frame, d, &candidates, hint, kInf);
      sum += Shade(scene, frame, d, hit, sample_angle);
      hint = hit.index;
    }
    return Rgb(sum * inv_samples);
  }

  void Store(int y, int x, const Rgb& radiance) const {
    const Rgb value = radiance * options.reflectance_scale;
    if (options.color) {
      output->radiance.ptr<cv::Vec3f>(y)[x] = cv::Vec3f(value.z(), value.y(), value.x());
    } else {
      output->radiance.ptr<float>(y)[x] = Luminance(value);
    }
  }
};

void RayCaster::Render(const Scene& scene, const perception::CameraModel& camera,
                       const Eigen::Isometry3d& T_WC, const RenderOptions& options,
                       RenderOutput* output) {
  if (options.supersampling < 1) {
    throw std::invalid_argument(
        "RenderOptions.supersampling = " + std::to_string(options.supersampling) + " must be >= 1");
  }
  if (!T_WC.matrix().allFinite()) {
    throw std::invalid_argument("RayCaster::Render: T_WC is not finite; pass a valid camera pose");
  }
  if (RenderProfile* profile = RenderProfileScope::Current()) ++profile->renders;
  std::optional<perception::ScopedCpuTimer> setup_timer(std::in_place,
                                                        RenderStage(&RenderProfile::setup_s));
  const int w = camera.width();
  const int h = camera.height();
  const int k = options.supersampling;
  const RayTable& rays = Rays(camera, k);

  std::vector<const SceneObject*> leds;
  FrameContext frame = PrepareFrameObjects(scene, T_WC, &leds);
  if (embree_) {
    embree_->Build(frame);
    frame.embree = embree_.get();
  } else {
    CullObjectsPerTile(rays.tile_axis, rays.tile_half_angle_rad, &frame);
  }

  const int image_type = options.color ? CV_32FC3 : CV_32FC1;
  output->radiance.create(h, w, image_type);
  if (options.ground_truth) {
    output->depth_C.create(h, w, CV_32FC1);
    output->object_id.create(h, w, CV_32SC1);
  } else {
    output->depth_C.release();
    output->object_id.release();
  }
  const bool adaptive = k > 1 && options.adaptive_supersampling;
  if (adaptive) {
    center_samples_.resize(rays.center.size());
    edge_pairs_.resize(rays.center.size());
  }
  const PixelPass pass{scene, frame, rays, options, output, w, k, 1.0f / static_cast<float>(k * k)};
  setup_timer.reset();
  {
    const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::centers_s));
    ShadePixelCenters(pass, h, adaptive);
  }
  if (adaptive) {
    const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::supersampling_s));
    SupersampleEdges(pass, h);
  }
  const perception::ScopedCpuTimer timer(RenderStage(&RenderProfile::leds_s));
  SplatLeds(leds, frame, camera, T_WC, options, output);
}

// Render step 3: one ray per pixel centre gives the ground truth, and the radiance for k = 1 and
// adaptive supersampling (which keeps the centre sample where it finds no edge); otherwise the
// pixel is supersampled at once.
void RayCaster::ShadePixelCenters(const PixelPass& pass, int h, bool adaptive) {
  const int w = pass.w;
  const int k = pass.k;
  const RayTable& rays = pass.rays;
  const FrameContext& frame = pass.frame;
  RenderOutput* output = pass.output;
  const bool ground_truth = pass.options.ground_truth;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& row_range) {
    std::vector<RayHit> row_hits(frame.embree ? static_cast<size_t>(w) : 0);
    for (int y = row_range.begin(); y < row_range.end(); ++y) {
      // Embree: the row's centre rays in packets first.
      if (frame.embree)
        frame.embree->NearestN(&rays.center[static_cast<size_t>(y) * w], w, row_hits.data());
      int hint = -1;  // per row, so results never depend on how rows are split among threads
      float* depth = ground_truth ? output->depth_C.ptr<float>(y) : nullptr;
      int32_t* ids = ground_truth ? output->object_id.ptr<int32_t>(y) : nullptr;
      for (int x = 0; x < w; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        const Eigen::Vector3d d = rays.center[p].cast<double>();
        const auto candidates = TileCandidates(frame, rays.Tile(x, y));
        const RayHit hit = frame.embree ? row_hits[static_cast<size_t>(x)]
                                        : NearestHit(frame, d, &candidates, hint, kInf);
        const int index = hit.index;
        if (depth) {
          depth[x] = index < 0 ? std::numeric_limits<float>::infinity()
                               : static_cast<float>(hit.local.t_m * d.z());
          ids[x] = index < 0 ? 0 : frame.objects[static_cast<size_t>(index)].id;
        }
        if (k == 1 || adaptive) {
          Rgb albedo;
          pass.Store(y, x, Shade(pass.scene, frame, d, hit, rays.pixel_angle_rad[p], &albedo));
          if (adaptive) {
            center_samples_[p] = CenterSample{
                index, index >= 0 && frame.objects[static_cast<size_t>(index)].hard_edged,
                Luminance(albedo),
                index < 0 ? Eigen::Vector3f(Eigen::Vector3f::Zero())
                          : Eigen::Vector3f(hit.local.n_O.cast<float>())};
          }
        } else {
          pass.Store(y, x, pass.Supersample(x, y, index));
        }
        hint = index;
      }
    }
  });
}

// Render step 4, adaptive supersampling: k x k rays where the centre samples show an edge. First
// each pixel compares itself with its right, lower-left, lower and lower-right neighbours (each
// of the 8 neighbour pairs once), then a pixel is supersampled when any pair touching it is an
// edge.
void RayCaster::SupersampleEdges(const PixelPass& pass, int h) {
  const int w = pass.w;
  enum : uint8_t { kRight = 1, kDownLeft = 2, kDown = 4, kDownRight = 8 };
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& row_range) {
    for (int y = row_range.begin(); y < row_range.end(); ++y) {
      const CenterSample* row = &center_samples_[static_cast<size_t>(y) * w];
      const CenterSample* below = y + 1 < h ? row + w : nullptr;
      uint8_t* pairs = &edge_pairs_[static_cast<size_t>(y) * w];
      for (int x = 0; x < w; ++x) {
        uint8_t bits = 0;
        if (x + 1 < w && row[x].EdgeTo(row[x + 1])) bits |= kRight;
        if (below) {
          if (x > 0 && row[x].EdgeTo(below[x - 1])) bits |= kDownLeft;
          if (row[x].EdgeTo(below[x])) bits |= kDown;
          if (x + 1 < w && row[x].EdgeTo(below[x + 1])) bits |= kDownRight;
        }
        pairs[x] = bits;
      }
    }
  });
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& row_range) {
    for (int y = row_range.begin(); y < row_range.end(); ++y) {
      const uint8_t* pairs = &edge_pairs_[static_cast<size_t>(y) * w];
      const uint8_t* above = y > 0 ? pairs - w : nullptr;
      for (int x = 0; x < w; ++x) {
        bool edge = pairs[x] != 0 || (x > 0 && (pairs[x - 1] & kRight));
        if (above && !edge) {
          edge = (above[x] & kDown) || (x > 0 && (above[x - 1] & kDownRight)) ||
                 (x + 1 < w && (above[x + 1] & kDownLeft));
        }
        if (edge) {
          pass.Store(y, x,
                     pass.Supersample(x, y, center_samples_[static_cast<size_t>(y) * w + x].index));
        }
      }
    }
  });
}

}  // namespace aperture::sim
