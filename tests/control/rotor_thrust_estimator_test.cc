#include "control/rotor_thrust_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "control/mixer.h"

namespace aperture::control {
namespace {

TEST(RotorThrustEstimator, FollowsAsymmetricFirstOrderModelG7) {
  const VehicleParameters vehicle;
  const double alpha_up = vehicle.rotor.time_constant_up_s;
  const double alpha_down = vehicle.rotor.time_constant_down_s;
  RotorThrustEstimator estimator(vehicle);
  EXPECT_TRUE(
      estimator.thrust_N().isApproxToConstant(0.25 * vehicle.mass_kg * vehicle.gravity_mps2));
  estimator.Reset(Eigen::Vector4d::Constant(1.0));
  // Rotors 0 and 2 step up to 2 N, rotors 1 and 3 down to 0.5 N, at the same time.
  RotorThrustCommand command;
  command.thrust_N = Eigen::Vector4d(2.0, 0.5, 2.0, 0.5);
  const double dt = 1e-3;
  for (int k = 1; k <= 40; ++k) {
    estimator.Propagate(command, dt);
    const double t = k * dt;
    // Analytic step responses; the zero-order-hold update is exact, so only round-off remains.
    EXPECT_NEAR(estimator.thrust_N()[0], 2.0 - std::exp(-t / alpha_up), 1e-12) << t;
    EXPECT_NEAR(estimator.thrust_N()[1], 0.5 + 0.5 * std::exp(-t / alpha_down), 1e-12) << t;
  }
  // Spinning up is faster than spinning down: after 20 ms the up step is closer to its target.
  estimator.Reset(Eigen::Vector4d::Constant(1.0));
  for (int k = 0; k < 20; ++k) estimator.Propagate(command, dt);
  EXPECT_LT(std::abs(estimator.thrust_N()[0] - 2.0) / 1.0,
            std::abs(estimator.thrust_N()[1] - 0.5) / 0.5);
  // Then back down from the reached value with alpha_down.
  const double f_reached = estimator.thrust_N()[0];
  command.thrust_N.setConstant(1.0);
  for (int k = 1; k <= 30; ++k) {
    estimator.Propagate(command, dt);
    EXPECT_NEAR(estimator.thrust_N()[0], 1.0 + (f_reached - 1.0) * std::exp(-k * dt / alpha_down),
                1e-12);
  }
}

TEST(RotorThrustEstimator, OneLongStepEqualsManyShortSteps) {
  const VehicleParameters vehicle;
  RotorThrustEstimator coarse(vehicle), fine(vehicle);
  RotorThrustCommand command;
  command.thrust_N = Eigen::Vector4d(0.3, 2.5, 1.0, 1.2);
  coarse.Propagate(command, 0.02);
  for (int k = 0; k < 200; ++k) fine.Propagate(command, 1e-4);
  EXPECT_TRUE(coarse.thrust_N().isApprox(fine.thrust_N(), 1e-12));
}

TEST(RotorThrustEstimator, TorqueEstimateUsesG1) {
  const VehicleParameters vehicle;
  RotorThrustEstimator estimator(vehicle);
  const Eigen::Vector4d thrust(1.3, 0.9, 1.1, 1.0);
  estimator.Reset(thrust);
  EXPECT_TRUE(estimator.BodyTorque_B().isApprox(BodyTorqueFromRotorThrusts(vehicle, thrust)));
  const double d = std::sqrt(2.0) / 2.0 * vehicle.arm_length_m;
  EXPECT_NEAR(estimator.BodyTorque_B().x(), d * (1.3 - 0.9 - 1.1 + 1.0), 1e-15);
}

TEST(RotorThrustEstimator, RejectsBadInput) {
  RotorThrustEstimator estimator{VehicleParameters()};
  RotorThrustCommand command;
  EXPECT_THROW(estimator.Propagate(command, 0.0), std::invalid_argument);
  command.thrust_N[1] = std::nan("");
  EXPECT_THROW(estimator.Propagate(command, 1e-3), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
