#pragma once
// The servo laws model a level vehicle: their camera twists carry no roll or pitch rate, and the
// image-moment law assumes the target plane keeps its orientation to the camera. A flying
// quadrotor tilts to accelerate, which moves every image point although the position has not
// changed. Re-projecting the points into the level camera C' (C's optical centre, the
// orientation C would have on the level body B': same heading as B, z_B' = z_W) with the
// attitude estimate removes that motion, as ViSP's drone examples rely on a gimbal-stabilized
// image for (Bebop 2 video stabilization). The camera's lever arm about B is not undone (that
// needs depth): a few mm for a 0.1 m mount at moderate tilt.
//
//   [x', y', 1] ~ R_C'C [x, y, 1],  R_C'C = R_BC^T R_B'B R_BC,  R_B'B = R_WB'^T R_WB,
//   R_WB' = Rz(psi), psi the heading of x_B (the yaw of R_WB).
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace aperture::servo {

// Points of the tilted camera (normalized coordinates) as the level camera sees them. Returns
// std::nullopt when a point falls behind the level camera (tilt of more than ~90 deg to it).
// Throws std::invalid_argument for non-finite input.
std::optional<std::vector<Eigen::Vector2d>> LevelView(const std::vector<Eigen::Vector2d>& points_n,
                                                      const Eigen::Matrix3d& R_WB,
                                                      const Eigen::Matrix3d& R_BC);

}  // namespace aperture::servo
