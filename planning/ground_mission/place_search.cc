#include "planning/ground_mission/place_search.h"

#include <algorithm>
#include <cmath>

namespace aperture::planning {
namespace {

bool PlaceIsFeasible(const PlaceSearchContext& context, const Eigen::Vector2d& p_W, double radius_m,
                     double robot_s_m, double grasp_s_m) {
  const GroundMissionScene& scene = *context.scene;
  if (((p_W - scene.area_min_W).array() < radius_m).any() ||
      ((scene.area_max_W - p_W).array() < radius_m).any()) {
    return false;
  }
  for (const GroundBox& box : scene.fixed_obstacles) {
    if (DistanceToBox(box, p_W) < radius_m) return false;
  }
  if ((p_W - scene.goal_p_W).norm() < radius_m + scene.goal_radius_m) return false;
  for (const auto* discs : {&context.in_place, &context.placed}) {
    for (const PlacedDisc& disc : *discs) {
      if ((p_W - disc.p_W).norm() < radius_m + disc.radius_m) return false;
    }
  }
  const GroundPolyline& path = *context.path;
  if (path.DistanceTo(p_W, robot_s_m, path.length_m()) < radius_m + context.robot_radius_m) {
    return false;
  }
  if (robot_s_m < grasp_s_m) {  // carried back: the stretch back to the grasp is driven again
    for (const PlacedDisc& disc : context.placed) {
      if (path.DistanceTo(disc.p_W, robot_s_m, grasp_s_m) <
          disc.radius_m + context.robot_radius_m) {
        return false;
      }
    }
  }
  return true;
}

// Left, then right of the path at arc length s_m.
std::optional<PlaceLocation> PlaceBeside(const PlaceSearchContext& context, double radius_m,
                                         double s_m, double grasp_s_m) {
  const Eigen::Vector2d robot_p_W = context.path->PointAt(s_m);
  const Eigen::Vector2d t_W = context.path->DirectionAt(s_m);
  const Eigen::Vector2d left_W(-t_W.y(), t_W.x());
  for (const double side : {1.0, -1.0}) {
    const Eigen::Vector2d p_W = robot_p_W + side * context.lateral_m * left_W;
    if (PlaceIsFeasible(context, p_W, radius_m, s_m, grasp_s_m)) return PlaceLocation{p_W, s_m};
  }
  return std::nullopt;
}

}  // namespace

std::optional<PlaceLocation> FindPlaceLocation(const PlaceSearchContext& context, double radius_m,
                                               double grasp_s_m, double forward_end_s_m) {
  const double step_m = context.step_m;
  const int forward_steps = static_cast<int>(std::floor((forward_end_s_m - grasp_s_m) / step_m));
  for (int k = 0; k <= forward_steps; ++k) {
    const double s_m = std::min(grasp_s_m + k * step_m, forward_end_s_m);
    if (auto place = PlaceBeside(context, radius_m, s_m, grasp_s_m)) return place;
  }
  const int backward_steps = static_cast<int>(std::ceil(grasp_s_m / step_m));
  for (int k = 1; k <= backward_steps; ++k) {
    const double s_m = std::max(grasp_s_m - k * step_m, 0.0);
    if (auto place = PlaceBeside(context, radius_m, s_m, grasp_s_m)) return place;
  }
  return std::nullopt;
}

}  // namespace aperture::planning
