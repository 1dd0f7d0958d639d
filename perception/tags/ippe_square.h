#pragma once
// Infinitesimal plane-based pose estimation of a square (IPPE, Collins & Bartoli, IJCV 2014,
// Sec. 4 and 5): both solutions of the planar ambiguity in closed form, from the four corners of a
// square tag in normalized image coordinates (x_C / z_C, y_C / z_C; undistorted).
//
// The corner homography H maps the tag plane to the image; its Jacobian J at the tag centre and
// the centre's image point v fix the rotation up to the mirror ambiguity: with R_v the rotation
// taking z_C onto the ray through v, J = (1 / t_z) B R~_22 where B = ([I_2 | -v] R_v)(:, 0:1), so
// A = B^-1 J has largest singular value gamma = 1 / t_z and R~_22 = A / gamma. The last row b of
// R~'s first two columns satisfies b b^T = I - R~_22^T R~_22 (rank one), and its two signs are the
// two solutions R = R_v R~. Each translation is the linear least-squares fit of the four corners'
// projection equations given R.
//
// Noise-free corners give the true pose exactly as one of the two. Costs a few microseconds
// (one 8x8 solve), where OpenCV's solvePnPGeneric(SOLVEPNP_IPPE_SQUARE) spends ~18 us on array
// handling; the result is the same (tests/perception/ippe_square_test.cc).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>

namespace aperture::perception {

// Corners in the order of TagCorner (tag_pose_estimator.h) for a tag of edge tag_size_m.
// std::nullopt when the corners do not define a homography (three or more collinear) or the
// result is not finite. The two poses are equal when the tag is seen exactly head-on.
std::optional<std::array<Eigen::Isometry3d, 2>> IppeSquare(
    const std::array<Eigen::Vector2d, 4>& corners_normalized, double tag_size_m);

}  // namespace aperture::perception
