#pragma once
// KinematicTrajectory: a scripted vehicle path T_WB(s) for rendering datasets (no dynamics), over
// progress s in [0, 1] (the first frame at s = 0, the last at s = 1). Kinds (TrajectoryParams):
//   hover   T_WB_start throughout;
//   line    position from the start to end_p_m, start attitude;
//   circle  about the vertical axis through center_p_m by arc_deg, yaw turning with the arc
//           (a camera that faces the centre at the start keeps facing it);
//   scan    line to end_p_m plus a lateral (body y) sinusoid of amplitude_m, `cycles` periods;
//   random  smooth seeded wander around the start: per axis a sum of three sinusoids (1-3
//           periods over the run, seeded phases) of amplitude_m and angle_amplitude_deg.
#include <Eigen/Geometry>
#include <cstdint>

#include "sim/scenario/scenario_params.h"

namespace aperture::sim {

class KinematicTrajectory {
 public:
  // seed: the scenario seed (random kind only).
  KinematicTrajectory(const TrajectoryParams& params, const Eigen::Isometry3d& T_WB_start,
                      std::uint64_t seed);

  // Pose at progress s (clamped to [0, 1]).
  Eigen::Isometry3d T_WB(double s) const;

 private:
  TrajectoryParams params_;
  Eigen::Isometry3d T_WB_start_;
  // random: phases [rad] of 3 sinusoids for x, y, z, roll, pitch, yaw.
  Eigen::Matrix<double, 6, 3> phases_rad_;
};

}  // namespace aperture::sim
