#include "control/vehicle_parameters.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace aperture::control {
namespace {

TEST(RotorParameters, CommandFromThrustInvertsThrustFromCommand) {
  const RotorParameters rotor;
  for (double u = -1.0; u <= 1.0; u += 0.01) {
    // The inverse is a square root of O(1) numbers: round-off ~1e-15.
    EXPECT_NEAR(rotor.CommandFromThrust(rotor.ThrustFromCommand(u)), u, 1e-12) << "u = " << u;
  }
  // Out-of-range thrusts clamp to the command range.
  EXPECT_NEAR(rotor.CommandFromThrust(100.0), rotor.command_max, 1e-12);
  EXPECT_NEAR(rotor.CommandFromThrust(0.0), rotor.command_min, 1e-12);
}

TEST(RotorParameters, CommandFromThrustHandlesLinearAndNearlyLinearMaps) {
  RotorParameters rotor;
  // Linear map (k2 = 0): the textbook root formula divides by zero.
  rotor.thrust_coeffs_N = Eigen::Vector3d(1.0, 0.9, 0.0);
  EXPECT_NEAR(rotor.CommandFromThrust(1.45), 0.5, 1e-15);
  // k2 = 1e-9: the textbook formula loses ~9 digits to cancellation.
  rotor.thrust_coeffs_N = Eigen::Vector3d(1.0, 0.9, 1e-9);
  for (const double u : {-0.9, -0.3, 0.2, 0.7}) {
    EXPECT_NEAR(rotor.CommandFromThrust(rotor.ThrustFromCommand(u)), u, 1e-14) << "u = " << u;
  }
  // A map with k1 < 0, rising on a command range above its vertex (u >= 0.25).
  rotor.thrust_coeffs_N = Eigen::Vector3d(0.2, -0.5, 1.0);
  rotor.command_min = 0.5;
  for (const double u : {0.5, 0.6, 0.8, 1.0}) {
    EXPECT_NEAR(rotor.CommandFromThrust(rotor.ThrustFromCommand(u)), u, 1e-12) << "u = " << u;
  }
}

TEST(RotorParameters, TorqueCoefficientIsDragTorqueOverThrust) {
  const RotorParameters rotor;
  for (double u = -1.0; u <= 1.0; u += 0.05) {
    const double f = rotor.ThrustFromCommand(u);
    // (G.5): kappa(f(u)) f(u) = tau(u).
    EXPECT_NEAR(rotor.TorqueCoefficient(f) * f, rotor.DragTorqueFromCommand(u), 1e-14)
        << "u = " << u;
  }
  // Table A.2: kappa = 0.0195 m at hover (m g / 4 = 1.10 N); the fit was made to give it to 1e-4.
  EXPECT_NEAR(rotor.TorqueCoefficient(0.45 * 9.81 / 4.0), 0.0195, 1e-4);
  // Fig. G.4 trend: kappa falls by about 10 % from low thrust to full thrust.
  const double kappa_low = rotor.TorqueCoefficient(0.12);
  const double kappa_high = rotor.TorqueCoefficient(rotor.MaxThrust());
  EXPECT_GT(kappa_low, kappa_high);
  EXPECT_NEAR((kappa_low - kappa_high) / kappa_low, 0.09, 0.03);
}

TEST(VehicleParameters, RotorGeometryReproducesG1) {
  const VehicleParameters vehicle;
  // Torque of rotor thrust f along z_B at r_i: r_i x (0, 0, f) must give the rows of (G.1).
  const double d = std::sqrt(2.0) / 2.0 * vehicle.arm_length_m;
  const Eigen::Vector4d f(0.7, 1.1, 1.3, 0.9);
  Eigen::Vector2d torque = Eigen::Vector2d::Zero();
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(vehicle.RotorPosition_B(i).head<2>().norm(), vehicle.arm_length_m, 1e-15);
    torque += vehicle.RotorPosition_B(i).cross(Eigen::Vector3d(0.0, 0.0, f[i])).head<2>();
  }
  EXPECT_NEAR(torque.x(), d * (f[0] - f[1] - f[2] + f[3]), 1e-15);
  EXPECT_NEAR(torque.y(), d * (-f[0] - f[1] + f[2] + f[3]), 1e-15);
  EXPECT_EQ(VehicleParameters::RotorYawSign(0), 1.0);
  EXPECT_EQ(VehicleParameters::RotorYawSign(1), -1.0);
  EXPECT_EQ(VehicleParameters::RotorYawSign(2), 1.0);
  EXPECT_EQ(VehicleParameters::RotorYawSign(3), -1.0);
}

TEST(VehicleParameters, ValidateAcceptsDefaultsAndNamesBadFields) {
  EXPECT_NO_THROW(VehicleParameters().Validate());
  auto expect_error_naming = [](const VehicleParameters& vehicle, const std::string& field) {
    try {
      vehicle.Validate();
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
    }
  };
  VehicleParameters vehicle;
  vehicle.mass_kg = 0.0;
  expect_error_naming(vehicle, "mass_kg");
  vehicle = VehicleParameters();
  vehicle.inertia_diag_kgm2.z() = std::nan("");
  expect_error_naming(vehicle, "inertia_diag_kgm2");
  vehicle = VehicleParameters();
  vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(1.0, -1.6, 0.1);  // decreasing
  expect_error_naming(vehicle, "thrust_coeffs_N");
  vehicle = VehicleParameters();
  vehicle.rotor.torque_coeffs_Nm = Eigen::Vector3d(0.0, 0.03, 0.0);  // negative for u < 0
  expect_error_naming(vehicle, "torque_coeffs_Nm");
  vehicle = VehicleParameters();
  vehicle.rotor_fitness[2] = -0.1;
  expect_error_naming(vehicle, "rotor_fitness");
}

}  // namespace
}  // namespace aperture::control
