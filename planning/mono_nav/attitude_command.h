#pragma once
// Attitude command for drones that take roll/pitch/climb commands (seed 003 Sec. III-F (35)-(36)):
// the planned acceleration (x'', y'', z'') in W at heading psi becomes
//   theta = arctan((x'' cos psi + y'' sin psi) / (z'' + g))             pitch, about y
//   phi   = arctan((x'' sin psi - y'' cos psi) / (z'' + g) * cos theta)  roll, about x
// so that R_WB = Rz(psi) Ry(theta) Rx(phi) points the thrust axis z_B along (x'', y'', z'' + g).
// (The paper's phi is positive for acceleration to the right of the heading, i.e. towards -y_B;
// with the z-up convention of DESIGN.md that is a positive rotation about x_B.) The model is
// singular at z'' = -g (free fall): the result is then nullopt.
#include <Eigen/Core>
#include <optional>

namespace aperture::planning {

struct AttitudeCommand {
  double roll_rad = 0.0;                 // phi
  double pitch_rad = 0.0;                // theta
  double climb_acceleration_mps2 = 0.0;  // z'' (the height command)
};

// acceleration_W: (x'', y'', z'') [m/s^2]; heading_rad: psi. nullopt when z'' + g <= 0.
std::optional<AttitudeCommand> AttitudeFromAcceleration(const Eigen::Vector3d& acceleration_W,
                                                        double heading_rad,
                                                        double gravity_mps2 = 9.81);

}  // namespace aperture::planning
