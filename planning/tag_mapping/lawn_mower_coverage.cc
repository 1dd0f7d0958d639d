#include "planning/tag_mapping/lawn_mower_coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace aperture::planning {
namespace {

// Border samples per image side for the footprint.
constexpr int kBorderSamples = 32;

}  // namespace

double CentralFocalLengthPx(const perception::CameraModel& camera) {
  constexpr double kStep_m = 1e-3;
  const Eigen::Vector2d centre_px(0.5 * (camera.width() - 1), 0.5 * (camera.height() - 1));
  const Eigen::Vector3d ray_C = camera.Unproject(centre_px);
  const Eigen::Vector3d p_C = ray_C / ray_C.z();  // depth 1 m
  double sum = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Vector2d a, b;
    const Eigen::Vector3d step = 0.5 * kStep_m * Eigen::Vector3d::Unit(axis);
    if (!camera.Project(p_C - step, &a) || !camera.Project(p_C + step, &b)) {
      throw std::invalid_argument("CentralFocalLengthPx: the camera does not see its own centre");
    }
    sum += (b - a).norm() / kStep_m;
  }
  return 0.5 * sum;
}

double MappingHeight(double focal_px, const std::vector<TagClass>& classes,
                     double min_tag_side_px) {
  if (!(focal_px > 0.0)) throw std::invalid_argument("MappingHeight: focal_px must be > 0");
  if (!(min_tag_side_px > 0.0)) {
    throw std::invalid_argument("MappingHeight: min_tag_side_px must be > 0");
  }
  if (classes.empty()) throw std::invalid_argument("MappingHeight: no tag classes given");
  double height_m = std::numeric_limits<double>::infinity();
  for (const TagClass& c : classes) {
    if (!(c.size_m > 0.0) || !std::isfinite(c.surface_height_m)) {
      throw std::invalid_argument("MappingHeight: a tag class has size " +
                                  std::to_string(c.size_m) +
                                  " m (must be > 0) or a non-finite surface height");
    }
    height_m = std::min(height_m, c.surface_height_m + focal_px * c.size_m / min_tag_side_px);
  }
  return height_m;
}

Footprint FootprintAtDepth(const perception::CameraModel& camera, double depth_m) {
  if (!(depth_m > 0.0)) throw std::invalid_argument("FootprintAtDepth: depth_m must be > 0");
  const double w = camera.width() - 1.0, h = camera.height() - 1.0;
  Footprint footprint{std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
  // The point on the plane z_C = depth_m along the ray through pixel (u, v).
  const auto on_plane = [&](double u, double v) {
    const Eigen::Vector3d ray_C = camera.Unproject(Eigen::Vector2d(u, v));
    if (!(ray_C.z() > 1e-9)) {
      throw std::invalid_argument(
          "FootprintAtDepth: an image border ray does not reach the ground (field of view >= 180 "
          "deg); a downward mapping camera needs a narrower one");
    }
    return Eigen::Vector2d(ray_C.head<2>() * (depth_m / ray_C.z()));
  };
  for (int k = 0; k <= kBorderSamples; ++k) {
    const double f = double(k) / kBorderSamples;
    // Left and right sides bound x, top and bottom bound y.
    footprint.half_x_m = std::min(
        {footprint.half_x_m, std::abs(on_plane(0.0, f * h).x()), std::abs(on_plane(w, f * h).x())});
    footprint.half_y_m = std::min(
        {footprint.half_y_m, std::abs(on_plane(f * w, 0.0).y()), std::abs(on_plane(f * w, h).y())});
  }
  return footprint;
}

LawnMowerPlan PlanLawnMower(const FieldRectangle& field, double camera_height_m,
                            double half_across_m, double half_along_m, double overlap) {
  const Eigen::Vector2d extent = field.max_W - field.min_W;
  if (!(extent.x() > 0.0 && extent.y() > 0.0)) {
    throw std::invalid_argument("PlanLawnMower: the field is empty (max_W must exceed min_W)");
  }
  if (!(half_across_m > 0.0 && half_along_m > 0.0)) {
    throw std::invalid_argument(
        "PlanLawnMower: the reduced footprint is empty (the largest tag does not fit in the "
        "image at this height)");
  }
  if (!(overlap >= 0.0 && overlap < 1.0)) {
    throw std::invalid_argument("PlanLawnMower: overlap must be in [0, 1)");
  }
  LawnMowerPlan plan;
  plan.half_across_m = half_across_m;
  plan.half_along_m = half_along_m;
  // Tracks along the longer side: axis `along` of W, `across` the other.
  const int along = extent.y() >= extent.x() ? 1 : 0;
  const int across = 1 - along;
  plan.track_direction_W = Eigen::Vector2d::Unit(along);
  const double inset_across = (1.0 - overlap) * half_across_m;
  const double inset_along = (1.0 - overlap) * half_along_m;
  const double span = extent(across) - 2.0 * inset_across;  // of the track positions
  plan.tracks = span <= 0.0 ? 1 : static_cast<int>(std::ceil(span / (2.0 * inset_across))) + 1;
  plan.track_spacing_m = plan.tracks > 1 ? span / (plan.tracks - 1) : 0.0;
  const double centre_across = 0.5 * (field.min_W(across) + field.max_W(across));
  const double centre_along = 0.5 * (field.min_W(along) + field.max_W(along));
  const double half_track = std::max(0.0, 0.5 * extent(along) - inset_along);
  for (int k = 0; k < plan.tracks; ++k) {
    const double position = plan.tracks > 1
                                ? field.min_W(across) + inset_across + k * plan.track_spacing_m
                                : centre_across;
    for (const double end : {-1.0, 1.0}) {
      Eigen::Vector3d p_W(0.0, 0.0, camera_height_m);
      p_W(across) = position;
      p_W(along) = centre_along + (k % 2 == 0 ? end : -end) * half_track;
      plan.camera_waypoints_W.push_back(p_W);
    }
  }
  return plan;
}

}  // namespace aperture::planning
