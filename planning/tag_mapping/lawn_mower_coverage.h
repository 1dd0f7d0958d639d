#pragma once
// Lawn-mower coverage of a rectangular tag field by a downward camera (issue 15, item 3; paper D's
// quadrotor "explores the area" at a fixed height before the map is optimized).
//
// Height rule: the highest flight that keeps every tag class resolvable. A tag of black-border
// edge s lying on a surface z_s, seen from height h straight below the camera, spans
//   s_px = f_px s / (h - z_s)  pixels,  f_px: the camera's magnification at its image centre
// (CentralFocalLengthPx; exact for a pinhole looking straight down, whose magnification is the
// same over a plane parallel to the image). So s_px >= min_tag_side_px holds for every class iff
//   h <= min over classes of  z_s + f_px s / min_tag_side_px,
// and that minimum is the height flown (higher sees more per track; lower buys nothing the rule
// asks for).
//
// Footprint: the rectangle, centred on the camera's nadir and aligned with the image axes, that
// the image border encloses on a horizontal plane at depth d below a level camera (the border
// sampled, each side's nearest point taken: exact for a pinhole looking straight down, inside the
// seen area for a distorted one). Coverage is planned on the highest tag surface (the smallest
// footprint) with each half extent shrunk by the largest tag's half diagonal, so a tag whose
// centre lies in that reduced footprint is wholly in the image.
//
// Tracks: parallel to the field's longer side, flown in alternating directions. With the reduced
// footprint's half extents a (across the tracks) and b (along), and the side overlap o:
//   * adjacent tracks are at most 2 a (1 - o) apart, so their footprints share >= 2 a o;
//   * the outer tracks lie (1 - o) a inside the field's long edges, so their footprints reach
//     o a beyond them; the track ends lie (1 - o) b inside the short edges, likewise;
//   * a field narrower than 2 a (1 - o) gets one track on its centre line (shorter than
//     2 b (1 - o): a track of zero length, a single view).
// Every point of the field is then inside the reduced footprint of some camera position on the
// tracks (tests/planning/lawn_mower_coverage_test.cc checks it on a grid).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::planning {

// Tags of one size lying on surfaces of one height (the field's ground, an obstacle's top).
struct TagClass {
  double size_m = 0.0;            // black-border edge [m]
  double surface_height_m = 0.0;  // z_W of the surface the tags lie on [m]
};

// The camera's magnification at its image centre [px per m at 1 m depth]: the mean over the two
// image axes of the pixel distance between the projections of points 1 mm apart at 1 m.
double CentralFocalLengthPx(const perception::CameraModel& camera);

// The height rule above [m, z_W of the camera]. std::invalid_argument for no classes, a
// non-positive size, focal length or pixel count.
double MappingHeight(double focal_px, const std::vector<TagClass>& classes, double min_tag_side_px);

// Half extents [m] of a footprint rectangle along the image's x (columns) and y (rows) axes.
struct Footprint {
  double half_x_m = 0.0;
  double half_y_m = 0.0;
};

// The footprint at depth_m below a level camera looking straight down (see above).
// std::invalid_argument for a non-positive depth or a border ray that does not look down.
Footprint FootprintAtDepth(const perception::CameraModel& camera, double depth_m);

// A field rectangle in W (z up), by its corners.
struct FieldRectangle {
  Eigen::Vector2d min_W = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_W = Eigen::Vector2d::Zero();
};

struct LawnMowerPlan {
  // The camera's path: track ends in flight order (two per track, alternating directions), at
  // the camera's height [m].
  std::vector<Eigen::Vector3d> camera_waypoints_W;
  Eigen::Vector2d track_direction_W = Eigen::Vector2d::UnitY();  // unit, along the tracks
  int tracks = 0;
  double track_spacing_m = 0.0;  // between adjacent tracks (0 with one track)
  // The reduced footprint's half extents across and along the tracks [m].
  double half_across_m = 0.0;
  double half_along_m = 0.0;
};

// Tracks over `field` for a camera at camera_height_m whose reduced footprint has the half extents
// half_across_m (across the tracks) and half_along_m, with side overlap `overlap` in [0, 1).
// std::invalid_argument for an empty field, non-positive half extents or overlap outside [0, 1).
LawnMowerPlan PlanLawnMower(const FieldRectangle& field, double camera_height_m,
                            double half_across_m, double half_along_m, double overlap);

}  // namespace aperture::planning
