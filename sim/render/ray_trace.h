#pragma once
// The renderer's ray-object step (ray_caster.cc), shared by its two intersection back ends:
// the scene's non-LED objects prepared for one frame in the camera frame C (FrameContext), the
// nearest hit of a ray among them (RayHit), and the tile-culling search over per-tile candidate
// lists (TraceRay). The Embree back end (embree_scene.h) builds its BVH from the same
// FrameContext and returns the same RayHit, so shading, textures and supersampling run on
// either back end's hits unchanged. Internal to sim/render.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "sim/scene/scene.h"

namespace aperture::sim {

class EmbreeScene;

constexpr double kMinT = 1e-9;  // ignore hits at the ray origin [m]
// Planar objects are rejected from the ray-plane distance in C before the exact test in O; the
// two computations of that distance differ by rounding (~1e-15 relative), so rejecting only
// beyond these margins never drops a hit the exact test would find.
constexpr double kPlaneRejectRelative = 1e-9;
constexpr double kPlaneRejectAbsolute_m = 1e-9;

// One non-LED object prepared for a frame: everything in or relative to the camera frame C.
struct FrameObject {
  const Primitive* primitive;
  const Material* material;
  int id;
  Eigen::Matrix3d R_OC;
  Eigen::Vector3d p_OC;        // camera centre in O
  Eigen::Vector3d to_light_O;  // unit vector towards the light, in O
  bool hard_edged;             // texture with hard edges (Texture::has_hard_edges)
  bool planar;                 // Rectangle or GroundPlane: the plane z_O = 0
  Eigen::Vector3d n_C;         // planar: z_O in C
  double plane_offset_m;       // planar: n_C . (origin of O in C)
  bool bounded;
  Eigen::Vector3d center_C;  // bounding sphere centre in C
  double center_sq;
  double radius;
  double radius_sq;
};

// A candidate object of an image tile with a lower bound on the distance t at which any ray of
// the tile can hit it (0 when unknown).
struct TileCandidate {
  int index;  // into FrameContext::objects
  double t_lower_m;
};

struct FrameContext {
  std::vector<FrameObject> objects;
  Eigen::Matrix3d R_WC;
  // Candidates per image tile, each list sorted by t_lower_m:
  // tile_candidates[tile_begin[t] .. tile_begin[t + 1]).
  std::vector<TileCandidate> tile_candidates;
  std::vector<size_t> tile_begin;
  std::vector<TileCandidate> all_objects;  // every object, t_lower_m = 0
  // Set when the Embree back end finds the hits (its BVH of this frame's objects); the tile
  // lists are then left empty.
  const EmbreeScene* embree = nullptr;

  // Candidate list of tile t.
  std::pair<const TileCandidate*, const TileCandidate*> Candidates(size_t t) const {
    return {tile_candidates.data() + tile_begin[t], tile_candidates.data() + tile_begin[t + 1]};
  }
};

// The nearest hit of a ray: object index (-1: none, sky), the hit in the object's frame and the
// ray direction in that frame.
struct RayHit {
  int index = -1;
  LocalHit local;
  Eigen::Vector3d d_O;
};

// Nearest hit along the unit ray d_C from the camera centre with t < t_max among the candidates
// [first, last) (sorted by t_lower_m). Tries `hint` first so its hit tightens t for the
// early-outs, and stops at the first candidate whose lower bound is not below the nearest hit.
inline RayHit TraceRay(const Eigen::Vector3d& d_C, const std::vector<FrameObject>& objects,
                       std::pair<const TileCandidate*, const TileCandidate*> candidates, int hint,
                       double t_max) {
  RayHit best;
  double best_t = t_max;
  auto test = [&](int i) {
    const FrameObject& f = objects[static_cast<size_t>(i)];
    if (f.bounded) {
      const double tca = f.center_C.dot(d_C);
      if (tca + f.radius < 0.0 || tca - f.radius >= best_t) return;
      if (f.center_sq - tca * tca > f.radius_sq) return;
    }
    if (f.planar) {
      // t = plane_offset / n_C.d outside [-absolute margin, best_t (1 + relative margin)],
      // without the division (best_t = inf gives +-inf bounds, which reject nothing).
      const double den = f.n_C.dot(d_C);
      const double near = -kPlaneRejectAbsolute_m * den;
      const double far = best_t * (1.0 + kPlaneRejectRelative) * den;
      if (den > 0.0 ? (f.plane_offset_m < near || f.plane_offset_m > far)
                    : (den < 0.0 && (f.plane_offset_m > near || f.plane_offset_m < far))) {
        return;
      }
    }
    const Eigen::Vector3d direction_O = f.R_OC * d_C;
    // Written in place (IntersectPrimitive leaves *hit alone on a miss): no copy of the hit.
    if (IntersectPrimitive(*f.primitive, f.p_OC, direction_O, kMinT, best_t, &best.local)) {
      best_t = best.local.t_m;
      best.index = i;
      best.d_O = direction_O;
    }
  };
  if (hint >= 0) test(hint);
  for (const TileCandidate* c = candidates.first; c != candidates.second; ++c) {
    if (c->t_lower_m >= best_t) break;
    if (c->index != hint) test(c->index);
  }
  return best;
}
}  // namespace aperture::sim
