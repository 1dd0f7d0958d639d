#include "sim/scenario/kinematic_trajectory.h"

#include <algorithm>
#include <cmath>

#include "control/constants.h"
#include "sim/scene/counter_hash.h"

namespace aperture::sim {
namespace {

using control::kDegToRad;

}  // namespace

KinematicTrajectory::KinematicTrajectory(const TrajectoryParams& params,
                                         const Eigen::Isometry3d& T_WB_start, std::uint64_t seed)
    : params_(params), T_WB_start_(T_WB_start) {
  for (int axis = 0; axis < 6; ++axis) {
    for (int k = 0; k < 3; ++k) {
      phases_rad_(axis, k) = 2.0 * M_PI * UniformFromHash(HashCounters(seed, 0x7A, axis, k));
    }
  }
}

Eigen::Isometry3d KinematicTrajectory::T_WB(double s) const {
  s = std::clamp(s, 0.0, 1.0);
  Eigen::Isometry3d T = T_WB_start_;
  const Eigen::Vector3d p0 = T_WB_start_.translation();
  const std::string& kind = params_.kind;
  if (kind == "line" || kind == "scan") {
    T.translation() = p0 + s * (params_.end_p_m - p0);
    if (kind == "scan") {
      const double lateral = params_.amplitude_m * std::sin(2.0 * M_PI * params_.cycles * s);
      T.translation() += T_WB_start_.linear().col(1) * lateral;
    }
  } else if (kind == "circle") {
    const Eigen::AngleAxisd turn(params_.arc_deg * kDegToRad * s, Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d c(params_.center_p_m.x(), params_.center_p_m.y(), p0.z());
    T.translation() = c + turn * (p0 - c);
    T.linear() = turn.toRotationMatrix() * T_WB_start_.linear();
  } else if (kind == "random") {
    // Sum of sinusoids with 1, 2 and 3 periods over the run, amplitudes 1/2, 1/3, 1/6 (sum 1),
    // each started at its seeded phase minus the phase at s = 0 (so the wander starts at 0).
    Eigen::Matrix<double, 6, 1> offset;
    for (int axis = 0; axis < 6; ++axis) {
      const double weights[3] = {0.5, 1.0 / 3.0, 1.0 / 6.0};
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double phase = phases_rad_(axis, k);
        sum += weights[k] * (std::sin(2.0 * M_PI * (k + 1) * s + phase) - std::sin(phase));
      }
      offset[axis] = sum;
    }
    T.translation() = p0 + params_.amplitude_m * offset.head<3>();
    const Eigen::Vector3d angles = params_.angle_amplitude_deg * kDegToRad * offset.tail<3>();
    T.linear() = (Eigen::AngleAxisd(angles.z(), Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(angles.y(), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(angles.x(), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix() *
                 T_WB_start_.linear();
  }
  return T;
}

}  // namespace aperture::sim
