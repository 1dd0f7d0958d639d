#pragma once
// The one pose measurement type every pose-producing front end publishes (Node::Poses): where a
// target frame X (the gap G, the LED target T, a tag) is relative to the camera C on one frame,
// with its uncertainty and with the frames named. `aperture run` writes it as a TUM stream
// (apps/pose_streams.h); missions fuse it with the IMU through one component
// (perception/estimation/pose_fusion.h), so a new front end needs no glue of its own to fly.
//
// Frames (STYLE.md 1): T_CX maps target points into the camera, p_C = T_CX * p_X. Exactly one of
// C and X is fixed in the world and the other one moves with the vehicle: a gap or a tag is
// fixed and the camera rides on the body; a ground camera is fixed and the LED target rides on
// the body. `fixed` says which, and with it what the observation measures about the vehicle.
//
// Covariance: 6x6 over the left perturbation T_CX <- (Exp(dr), dt) * T_CX, delta = [dt (m); dr
// (rad)] in C, i.e. p_CX <- Exp(dr) p_CX + dt and R_CX <- Exp(dr) R_CX (the gap detector's form;
// a front end whose refinement perturbs differently converts, e.g. the LED tracker's p_CX + dt).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace aperture::perception {

struct PoseObservation {
  enum class Fixed {
    kTarget,  // X is fixed in the world, C moves (gap, tags): the stream records T_XC
    kCamera,  // C is fixed in the world, X moves (LED target on the vehicle): records T_CX
  };

  std::string stream;        // "gap", "led": the TUM file <stream>.csv and the fusion's key
  std::string target_frame;  // name of X for logs and docs: "G", "T", "tag7"
  Fixed fixed = Fixed::kTarget;
  double t_s = 0.0;          // the frame's (mid-exposure) time [s]
  Eigen::Isometry3d T_CX = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Matrix<double, 6, 6>> covariance_CX;  // see the header comment

  // The moving frame's pose in the fixed one, the trajectory a TUM stream records: T_XC for a
  // fixed target (the camera's path in the gap frame), T_CX for a fixed camera.
  Eigen::Isometry3d T_fixed_moving() const;
  // Its covariance over the same kind of left perturbation, in the fixed frame.
  std::optional<Eigen::Matrix<double, 6, 6>> covariance_fixed_moving() const;
};

}  // namespace aperture::perception
