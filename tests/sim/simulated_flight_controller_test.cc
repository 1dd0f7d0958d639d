#include "sim/sitl/simulated_flight_controller.h"

#include <gtest/gtest.h>

namespace aperture::sim {
namespace {

TEST(SimulatedFlightController, IdlesWithoutCommandAndClampsPassThroughThrusts) {
  const control::VehicleParameters vehicle;
  SimulatedFlightController controller(vehicle);
  const double f_min = vehicle.rotor.MinThrust(), f_max = vehicle.rotor.MaxThrust();
  EXPECT_TRUE(controller.Step().thrust_N.isApprox(Eigen::Vector4d::Constant(f_min)));
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kRotorThrusts;
  command.rotor_thrusts.thrust_N << 1.0, -1.0, 10.0, 2.0;
  controller.SetCommand(command);
  const Eigen::Vector4d out = controller.Step().thrust_N;
  EXPECT_EQ(out, Eigen::Vector4d(1.0, f_min, f_max, 2.0));
}

TEST(SimulatedFlightController, HoverCommandGivesEqualHoverThrusts) {
  const control::VehicleParameters vehicle;
  SimulatedFlightController controller(vehicle);
  const double hover_N = vehicle.mass_kg * vehicle.gravity_mps2 / 4.0;
  controller.ResetThrustEstimate(Eigen::Vector4d::Constant(hover_N));
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates.collective_thrust_mps2 = vehicle.gravity_mps2;
  controller.SetCommand(command);
  // Zero rates demanded and measured: no torque, the mixer splits m g evenly (G.1).
  const Eigen::Vector4d out = controller.Step().thrust_N;
  EXPECT_TRUE(out.isApprox(Eigen::Vector4d::Constant(hover_N), 1e-6)) << out.transpose();
  // A measured roll rate makes the LQR oppose it: rotors on +y_B (1, 4) push harder than -y_B.
  controller.SetGyro(Eigen::Vector3d(-1.0, 0.0, 0.0));
  const Eigen::Vector4d roll = controller.Step().thrust_N;
  EXPECT_GT(roll(0) + roll(3), roll(1) + roll(2));
}

TEST(SimulatedFlightController, RejectsNonPositiveRate) {
  SimulatedFlightControllerParams params;
  params.rate_hz = 0.0;
  EXPECT_THROW(SimulatedFlightController(control::VehicleParameters(), params),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
