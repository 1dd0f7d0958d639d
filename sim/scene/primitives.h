#pragma once
// Geometric primitives of the simulator scene and their ray intersection, all in the object's
// own frame O. Each primitive defines surface coordinates (u, v) [m] along its surface, used to
// look up textures (textures.h):
//   Rectangle   in the plane z_O = 0, |x_O| <= size.x/2, |y_O| <= size.y/2, minus its holes.
//               Seen looking along +z_O, x_O points right and y_O down (like an image and like
//               an OpenCV/AprilTag object frame), so u = x_O + size.x/2, v = y_O + size.y/2
//               (origin at the top-left corner) show a texture unmirrored from that side.
//               Both sides are visible.
//   Box         |x_O|,|y_O|,|z_O| <= size/2; u, v are the two face coordinates (from the face's
//               lower corner) in the order x, y, z without the face's normal axis.
//   Cylinder    vertical (axis z_O), radius, z_O in [0, height], with end caps; mantle
//               u = radius * azimuth (from +x_O towards +y_O, in [0, 2 pi r)), v = z_O; caps
//               u = x_O, v = y_O.
//   Sphere      centred at O; u = radius * azimuth, v = radius * elevation.
//   GroundPlane infinite plane z_O = 0; u = x_O, v = y_O.
//   Led         small spherical emitter at O; not hit by rays: the renderer draws it as a
//               radiance blob (ray_caster.h). radius_m sets the blob size, intensity its energy,
//               radiation_exponent its pattern about +z_O.
#include <Eigen/Core>
#include <limits>
#include <variant>
#include <vector>

#include "sim/scene/textures.h"

namespace aperture::sim {

struct EllipseHole {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  // (x_O, y_O) of the centre [m]
  Eigen::Vector2d semi_axes_m = Eigen::Vector2d(0.1, 0.1);  // along the rotated x / y axis [m]
  double angle_rad = 0.0;  // rotation of the first semi-axis from x_O towards y_O
};

struct Rectangle {
  Eigen::Vector2d size_m = Eigen::Vector2d(1.0, 1.0);  // extent along x_O, y_O [m]
  // Holes in (x_O, y_O) [m]: simple polygons (any orientation, >= 3 vertices) and ellipses.
  std::vector<std::vector<Eigen::Vector2d>> polygon_holes;
  std::vector<EllipseHole> ellipse_holes;
};

struct Box {
  Eigen::Vector3d size_m = Eigen::Vector3d(1.0, 1.0, 1.0);  // full edge lengths [m]
};

struct Cylinder {
  double radius_m = 0.15;
  double height_m = 3.0;  // from z_O = 0 up
};

struct Sphere {
  double radius_m = 0.5;
};

struct GroundPlane {};

struct Led {
  double radius_m = 0.005;  // emitter radius; the blob's sigma is half its projected radius
  // Energy of the image blob at 1 m [radiance units * px^2]; falls off with 1 / distance^2.
  double intensity = 400.0;
  Rgb color = Rgb::Ones();
  // Radiation pattern: the energy times cos^m of the angle between the emitter's axis +z_O and
  // the direction to the camera (m = 1: Lambertian, half power at 60 deg like a wide-angle SMD
  // LED); nothing is seen from behind the emitter's plane. 0: isotropic.
  double radiation_exponent = 0.0;
};

using Primitive = std::variant<Rectangle, Box, Cylinder, Sphere, GroundPlane, Led>;

// Intersection of a ray with a primitive, in O.
struct LocalHit {
  double t_m = std::numeric_limits<double>::infinity();  // ray parameter (distance for unit d)
  Eigen::Vector3d n_O = Eigen::Vector3d::Zero();  // unit surface normal (outward, or +z_O)
  Eigen::Vector2d uv_m = Eigen::Vector2d::Zero();  // surface coordinates (see above)
};

// Nearest intersection of the ray o_O + t d_O with t in (t_min, t_max). d_O need not be unit
// (t is then in units of |d_O|). Returns false on a miss, leaving *hit unchanged; Led never
// hits. Throws nothing.
bool IntersectPrimitive(const Primitive& primitive, const Eigen::Vector3d& o_O,
                        const Eigen::Vector3d& d_O, double t_min, double t_max, LocalHit* hit);

// Bounding sphere (centre in O, radius) enclosing the primitive, for early-outs; the radius is
// infinite for GroundPlane.
double BoundingRadius(const Primitive& primitive);
Eigen::Vector3d BoundingCenter(const Primitive& primitive);

// Throws std::invalid_argument naming the field when a size is not positive or finite or a hole
// is degenerate.
void ValidatePrimitive(const Primitive& primitive);

}  // namespace aperture::sim
