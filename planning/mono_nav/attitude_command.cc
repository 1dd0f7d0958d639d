#include "planning/mono_nav/attitude_command.h"

#include <cmath>

namespace aperture::planning {

std::optional<AttitudeCommand> AttitudeFromAcceleration(const Eigen::Vector3d& acceleration_W,
                                                        double heading_rad, double gravity_mps2) {
  const double vertical = acceleration_W.z() + gravity_mps2;
  if (!(vertical > 0.0) || !acceleration_W.allFinite()) return std::nullopt;
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  AttitudeCommand command;
  command.pitch_rad = std::atan((acceleration_W.x() * c + acceleration_W.y() * s) / vertical);
  command.roll_rad = std::atan((acceleration_W.x() * s - acceleration_W.y() * c) / vertical *
                               std::cos(command.pitch_rad));
  command.climb_acceleration_mps2 = acceleration_W.z();
  return command;
}

}  // namespace aperture::planning
