#include "sim/vehicle/disturbances.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace aperture::sim {
namespace {

QuadrotorDynamics MakeHoveringVehicle(const QuadrotorDynamicsParams& params) {
  QuadrotorDynamics vehicle(params);
  control::RotorThrustCommand command;
  command.thrust_N.setConstant(params.vehicle.mass_kg * params.vehicle.gravity_mps2 / 4.0);
  vehicle.SetRotorThrustCommand(command);
  vehicle.SettleRotors();
  return vehicle;
}

TEST(DisturbancesTest, GustsAddToSteadyWindWhileActive) {
  DisturbanceParams params;
  params.steady_wind_W_mps = Eigen::Vector3d(1.0, 0.0, 0.0);
  params.gusts.push_back({1.0, 2.0, Eigen::Vector3d(0.0, 2.0, 0.0)});
  params.gusts.push_back({2.0, 0.5, Eigen::Vector3d(0.0, 0.0, -1.0)});
  const Disturbances disturbances(params);
  EXPECT_TRUE(disturbances.WindVelocity_W(0.99).isApprox(Eigen::Vector3d(1.0, 0.0, 0.0)));
  EXPECT_TRUE(disturbances.WindVelocity_W(1.0).isApprox(Eigen::Vector3d(1.0, 2.0, 0.0)));
  EXPECT_TRUE(disturbances.WindVelocity_W(2.2).isApprox(Eigen::Vector3d(1.0, 2.0, -1.0)));
  EXPECT_TRUE(disturbances.WindVelocity_W(3.0).isApprox(Eigen::Vector3d(1.0, 0.0, 0.0)));
}

TEST(DisturbancesTest, PushChangesVelocityByImpulseOverMassAtItsOwnTime) {
  QuadrotorDynamicsParams vehicle_params;
  vehicle_params.vehicle.rotor_drag_D_per_s.setZero();  // the velocity then stays after the push
  QuadrotorDynamics vehicle = MakeHoveringVehicle(vehicle_params);
  DisturbanceParams params;
  const double t_push = 0.0105;  // between two 1 ms steps: the step must be split
  const Eigen::Vector3d impulse_W(0.9, -0.45, 0.0);
  const Eigen::Vector3d angular_impulse_B(0.0, 0.0, 2e-3);
  params.pushes.push_back({t_push, impulse_W, angular_impulse_B});
  Disturbances disturbances(params);
  for (int k = 0; k < 10; ++k) disturbances.StepVehicle(0.001, &vehicle);
  EXPECT_EQ(disturbances.pushes_applied(), 0);
  EXPECT_NEAR(vehicle.state().v_W.norm(), 0.0, 1e-12);
  for (int k = 0; k < 90; ++k) disturbances.StepVehicle(0.001, &vehicle);
  EXPECT_EQ(disturbances.pushes_applied(), 1);
  const Eigen::Vector3d dv_W = impulse_W / vehicle_params.vehicle.mass_kg;
  EXPECT_TRUE(vehicle.state().v_W.isApprox(dv_W, 1e-12)) << vehicle.state().v_W.transpose();
  // Free flight at constant velocity since t_push: the split step puts the push at its time.
  EXPECT_TRUE(vehicle.state().p_WB.isApprox(dv_W * (0.1 - t_push), 1e-9));
  const double omega_z = 2e-3 / vehicle_params.vehicle.inertia_diag_kgm2.z();
  EXPECT_NEAR(vehicle.state().omega_B.z(), omega_z, 1e-12);
}

TEST(DisturbancesTest, GustDragsVehicleTowardsWindAsF2Predicts) {
  QuadrotorDynamicsParams vehicle_params;  // d_x = 0.5
  QuadrotorDynamics vehicle = MakeHoveringVehicle(vehicle_params);
  DisturbanceParams params;
  const double t0 = 0.5, duration = 1.0, wind = 3.0;
  params.gusts.push_back({t0, duration, Eigen::Vector3d(wind, 0.0, 0.0)});
  Disturbances disturbances(params);
  const double d = vehicle_params.vehicle.rotor_drag_D_per_s.x();
  // Steps of 0.7 ms do not land on the gust edges: the wind must still switch exactly there.
  while (vehicle.state().t_s < 2.0 - 1e-9) disturbances.StepVehicle(0.0007, &vehicle);
  // v' = -d (v - w): v = w (1 - exp(-d (t - t0))) during the gust, then decays from v(t0 + T).
  const double v_end_gust = wind * (1.0 - std::exp(-d * duration));
  const double t = vehicle.state().t_s;
  const double expected = v_end_gust * std::exp(-d * (t - t0 - duration));
  EXPECT_NEAR(vehicle.state().v_W.x(), expected, 1e-9);
  EXPECT_NEAR(vehicle.state().v_W.y(), 0.0, 1e-12);
}

TEST(DisturbancesTest, ConstantBodyTorqueSpinsUpHoveringVehicleAsJOmegaDotPredicts) {
  QuadrotorDynamicsParams vehicle_params;
  QuadrotorDynamics vehicle = MakeHoveringVehicle(vehicle_params);
  DisturbanceParams params;
  params.torque_B_Nm = Eigen::Vector3d(0.0, 0.0, 2e-4);  // about z_B only: omega x J omega = 0
  Disturbances disturbances(params);
  for (int k = 0; k < 100; ++k) disturbances.StepVehicle(0.001, &vehicle);
  // Equal hover thrusts give no rotor torque, rotor_drag_B = 0: r' = tau_z / J_zz exactly.
  const double expected = 2e-4 / vehicle_params.vehicle.inertia_diag_kgm2.z() * 0.1;
  EXPECT_NEAR(vehicle.state().omega_B.z(), expected, 1e-9);
  EXPECT_NEAR(vehicle.state().omega_B.head<2>().norm(), 0.0, 1e-12);
}

TEST(DisturbancesTest, ValidateNamesTheBadEntry) {
  DisturbanceParams params;
  params.gusts.push_back({0.0, 1.0, Eigen::Vector3d::Zero()});
  params.gusts.push_back({1.0, 0.0, Eigen::Vector3d::Zero()});
  try {
    params.Validate();
    FAIL() << "zero gust duration accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gusts[1].duration_s"), std::string::npos) << e.what();
  }
  params.gusts.pop_back();
  params.pushes.push_back({NAN, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  EXPECT_THROW(Disturbances{params}, std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
