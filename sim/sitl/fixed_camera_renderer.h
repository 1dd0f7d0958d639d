#pragma once
// Renders a camera fixed in the world (SitlCamera::T_WC_fixed, e.g. the `led` scenario's ground
// camera) frame after frame at a fraction of RayCaster's cost, with the same output: the scene
// without the objects that have moved is rendered once (the background), and each frame only the
// pixel rectangle that the moved objects can reach is ray cast again, with the whole scene.
//
// Why the result equals a full render: shading has no shadows or reflections (ray_caster.h), so a
// pixel depends only on the objects its own rays (and its 8 neighbours' centres, for adaptive
// supersampling) meet, plus LED blobs, which cover at most 4.5 sigma around their projection.
// The re-rendered rectangle covers each moved object's bounding sphere (projected through its
// camera-aligned bounding cube, a convex hull for a pinhole), the LED blob windows and 2 px for
// the neighbour rule and pixel footprints, and is ray cast with 2 px more around it; its rays are
// the full camera's (a pinhole with a shifted principal point, exact in floating point).
// An object counts as moved once its pose differs from the background's (the background is then
// rendered again without it). Contract: between frames only object poses change (not materials,
// lighting or sky, the camera pose or the object list; a new list or other RenderOptions restart
// the background). Other camera models than pinhole (or a moved object reaching behind the
// camera, or a rectangle over half the image) fall back to full renders.
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "perception/camera/camera_model.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/scene.h"

namespace aperture::sim {

class FixedCameraRenderer {
 public:
  FixedCameraRenderer(const perception::CameraModel& camera, const Eigen::Isometry3d& T_WC);

  // As RayCaster::Render(scene, camera, T_WC, options, output).
  void Render(const Scene& scene, const RenderOptions& options, RenderOutput* output);

  int background_renders() const { return background_renders_; }
  // Pixels ray cast by the last Render over the image's pixels (1 for a full render).
  double last_render_fraction() const { return last_render_fraction_; }

 private:
  bool UpdateBackground(const Scene& scene, const RenderOptions& options);
  // *region: the pixels the moved objects can reach (empty when none projects). false when that
  // cannot be bounded (full render).
  bool MovedRegion(const Scene& scene, const RenderOptions& options, cv::Rect* region) const;

  std::unique_ptr<perception::CameraModel> camera_;
  Eigen::Isometry3d T_WC_;
  bool pinhole_;
  RayCaster caster_;
  RenderOutput background_;
  RenderOptions background_options_;
  std::vector<Eigen::Isometry3d> background_poses_;  // per object, at the background render
  std::vector<bool> moved_;                          // per object: left out of the background
  int background_renders_ = 0;
  double last_render_fraction_ = 1.0;
};

}  // namespace aperture::sim
