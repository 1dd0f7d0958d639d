#pragma once
// The renderer's Embree back end (RayBackend::kEmbree, ray_caster.h): Intel Embree 3's BVH
// finds the nearest object of each ray; our exact intersection then gives the hit record, so
// the shading, textures and supersampling of ray_caster.cc run unchanged on its hits.
//
// Per frame, the frame's bounded objects go into one Embree scene in the camera frame C:
// Rectangles as 2 triangles and Boxes as 12 (float, Embree's own SIMD triangle test);
// Rectangles with holes get an intersection filter that accepts a triangle hit only where our
// exact test (IntersectPrimitive, double) hits, so the holes are exact; Cylinders and Spheres
// are user geometry whose intersect callback is IntersectPrimitive itself. Unbounded objects
// (GroundPlane) stay out of the BVH and are tested per ray up to Embree's hit. Rays go in
// packets of 16 neighbouring pixels (NearestN). The hit record of Embree's nearest object (t,
// normal, surface coordinates in double) is our callback's when one computed it, else one more
// IntersectPrimitive call: the same call the tile-culling back end makes, so the two give the
// same hits. Where Embree's float triangle and the double test disagree at an edge (rare), the
// ray falls back to the exact search over all objects; hits can then differ from the
// tile-culling back end only where Embree misses a triangle the double test would hit, at edges
// (none in tests/sim/render_backend_test.cc's views).
#include <Eigen/Core>
#include <memory>

#include "sim/render/ray_trace.h"

namespace aperture::sim {

// True when this build has Embree (CMake option APERTURE_EMBREE).
bool EmbreeAvailable();

class EmbreeScene {
 public:
  // Throws std::runtime_error when the build has no Embree (EmbreeAvailable()) or Embree fails
  // to start.
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Rebuilds the BVH over frame.objects. frame must stay alive and unchanged while Nearest is
  // called for it.
  void Build(const FrameContext& frame);

  // Nearest hit along the unit ray d_C from the camera centre with t < t_max among all of the
  // built frame's objects: the result TraceRay gives over all of them. Thread-safe.
  RayHit Nearest(const Eigen::Vector3d& d_C, double t_max) const;
  // Nearest(d_C[i], infinity) for the n rays d_C[0 .. n), traced in Embree ray packets (coherent
  // rays: neighbouring pixels).
  void NearestN(const Eigen::Vector3f* d_C, int n, RayHit* hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aperture::sim
