#include "planning/body_velocity_tracking.h"

#include <Eigen/Geometry>

namespace aperture::planning {

control::TrajectoryPoint BodyVelocityTrajectoryPoint(double t_s,
                                                     const Eigen::Vector3d& p_WB_estimate,
                                                     double heading_rad, const Eigen::Vector3d& v_B,
                                                     double heading_rate_radps) {
  control::TrajectoryPoint reference;
  reference.t_s = t_s;
  reference.p_W = p_WB_estimate;
  reference.v_W = Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()) * v_B;
  reference.heading_rad = heading_rad;
  reference.heading_rate_radps = heading_rate_radps;
  return reference;
}

}  // namespace aperture::planning
