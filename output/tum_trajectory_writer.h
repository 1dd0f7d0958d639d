#pragma once
// TumTrajectoryWriter: a trajectory in the TUM RGB-D format read by evo, rpg_trajectory_evaluation
// and the TUM scripts: one pose per line, "t tx ty tz qx qy qz qw" (space separated, w last),
// preceded by one '#' comment line. The pose is T_WB (body in world): t = p_WB, q = q_WB.
// Written atomically (see AtomicFile).
//
//   TumTrajectoryWriter tum(out.Path("estimate.tum"));
//   tum.Write(state.t_s, T_WB);
//   tum.Close();
#include <Eigen/Geometry>
#include <string>

#include "output/atomic_file.h"

namespace aperture::output {

class TumTrajectoryWriter {
 public:
  explicit TumTrajectoryWriter(const std::string& path);

  // The quaternion is normalised before writing. std::invalid_argument (naming the file and time)
  // for a non-finite time/position or a quaternion that cannot be normalised.
  void Write(double t_s, const Eigen::Vector3d& p_WB, const Eigen::Quaterniond& q_WB);
  void Write(double t_s, const Eigen::Isometry3d& T_WB);

  void Close() { file_.Commit(); }
  std::size_t poses_written() const { return poses_written_; }

 private:
  AtomicFile file_;
  std::size_t poses_written_ = 0;
};

}  // namespace aperture::output
