#pragma once
// The reference a velocity-commanding law (a visual servo: servo/body_velocity_reference.h)
// hands control::PositionController: the position reference rides on the estimate, so only
// the velocity is tracked (no position feedback to fight the servo), v_B is the velocity in the
// level body frame (heading heading_rad about z_W) and the heading turns at heading_rate_radps.
#include <Eigen/Core>

#include "control/trajectory_point.h"

namespace aperture::planning {

control::TrajectoryPoint BodyVelocityTrajectoryPoint(double t_s,
                                                     const Eigen::Vector3d& p_WB_estimate,
                                                     double heading_rad, const Eigen::Vector3d& v_B,
                                                     double heading_rate_radps = 0.0);

}  // namespace aperture::planning
