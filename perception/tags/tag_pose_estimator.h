#pragma once
// Pose T_CT of one square tag from its four corners (p_C = T_CT * p_T; T as in tag_detector.h:
// x right, y down, z into the tag, origin at the centre, corners at (+-s/2, +-s/2, 0)).
//
// 1. The distorted corners are undistorted through the calibration's camera model
//    (CameraModel::Unproject, any model incl. fisheye) to normalized image coordinates.
// 2. Infinitesimal plane-based pose estimation from the corner homography (IppeSquare,
//    ippe_square.h; Collins & Bartoli, IJCV 2014, Sec. 4) gives BOTH solutions of the planar
//    ambiguity: a plane seen under weak perspective fits two mirror-image tilts.
// 3. Each is refined by Gauss-Newton on the reprojection error in the distorted image (Faessler
//    thesis (C.8); RefineLedPose, which takes any camera model), giving the 6x6 covariance
//    Sigma = sigma^2 (J^T J)^-1 of [p_CT [m]; rotation [rad], perturbation of R_CT on the left
//    in C] ((C.9), led_pose_refiner.h) as its by-product.
// The candidate with the lower refined error is `best`; ambiguity_ratio = best error /
// alternative error (sums of squares) is near 1 when the two cannot be told apart (small or
// distant tags seen head-on) and near 0 when the image decides. TagFlipResolver picks between
// them over time and across tags.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "perception/camera/camera_model.h"
#include "perception/led/led_pose_refiner.h"

namespace aperture::perception {

struct TagPoseParams {
  // sigma of the corner noise for the covariance [px]; Gauss-Newton settings (2-4 steps suffice
  // from IPPE's start).
  LedPoseRefinerParams refiner;
  // Refined candidates whose rotations differ by less than this are one solution (IPPE's
  // second start converged to the first) [deg].
  double same_solution_deg = 2.0;
};

struct TagPoseCandidate {
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Zero();  // [p_CT [m]; rotation [rad]]
  double rms_px = 0.0;                     // RMS corner reprojection error at T_CT
};

struct TagPose {
  TagPoseCandidate best;
  std::optional<TagPoseCandidate> alternative;  // the other ambiguity solution, if distinct
  double ambiguity_ratio = 0.0;                 // in [0, 1]; 0 without an alternative
};

// std::nullopt when a corner's ray does not point in front of the camera (z_C <= 0: a fisheye
// beyond 90 deg) or Gauss-Newton fails. std::invalid_argument for tag_size_m <= 0.
std::optional<TagPose> EstimateTagPose(const CameraModel& camera,
                                       const std::array<Eigen::Vector2d, 4>& corners_px,
                                       double tag_size_m, const TagPoseParams& params = {});

// Corner k of a tag of edge tag_size_m in T (the order of tag_detector.h).
Eigen::Vector3d TagCorner(int k, double tag_size_m);

}  // namespace aperture::perception
