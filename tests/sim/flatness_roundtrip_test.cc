// Flatness inputs replayed open loop through the simulated vehicle reproduce the reference
// (STYLE.md 12): control::ComputeFlatnessOutputs (Faessler thesis Appendix F) and
// sim::QuadrotorDynamics (F.1)-(F.5) must describe the same vehicle, rotor drag included.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "control/flatness.h"
#include "control/reference_trajectories.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {
namespace {

// Rotor thrusts that produce m c_cmd and tau_B through (G.1), (G.2) with kappa_i = kappa(f_i) of
// (G.5): a fixed-point iteration on kappa (it varies by ~10 % over the thrust range, so a few
// iterations converge to machine precision). Kept local: the test must not depend on the
// controller's mixer, whose saturation logic is not the subject here.
Eigen::Vector4d MixExactly(double thrust_command_mps2, const Eigen::Vector3d& tau_B,
                           const control::VehicleParameters& vehicle) {
  const double a = std::sqrt(2.0) / 2.0 * vehicle.arm_length_m;
  const Eigen::Vector4d wrench(vehicle.mass_kg * thrust_command_mps2, tau_B.x(), tau_B.y(), tau_B.z());
  Eigen::Vector4d f = Eigen::Vector4d::Constant(wrench[0] / 4.0);
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::Matrix4d M;
    M.row(0) << 1, 1, 1, 1;
    M.row(1) << a, -a, -a, a;
    M.row(2) << -a, -a, a, a;
    for (int i = 0; i < 4; ++i) {
      M(3, i) = control::VehicleParameters::RotorYawSign(i) * vehicle.rotor.TorqueCoefficient(f[i]);
    }
    f = M.partialPivLu().solve(wrench);
  }
  return f;
}

struct RoundTripCase {
  std::string name;
  std::shared_ptr<const control::ReferenceTrajectory> trajectory;
  double t_start_s;
};

class FlatnessRoundTripTest : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(FlatnessRoundTripTest, OpenLoopInputsReproduceTrajectoryForOneSecond) {
  QuadrotorDynamicsParams params;
  control::VehicleParameters& vehicle = params.vehicle;
  // Every drag term of (F.2), (F.4), (F.5) switched on so both sides must agree on all of them.
  vehicle.rotor_drag_D_per_s = Eigen::Vector3d(0.5, 0.35, 0.1);
  vehicle.thrust_velocity_coeff_kh = 0.01;
  vehicle.rotor_drag_A = 1e-4 * Eigen::Matrix3d::Identity();
  vehicle.rotor_drag_B = 2e-4 * Eigen::Matrix3d::Identity();
  // Flatness assumes thrust and torque follow their commands instantly: no rotor lag (G.7).
  params.rotor_lag_enabled = false;

  const control::ReferenceTrajectory& trajectory = *GetParam().trajectory;
  const double t0 = GetParam().t_start_s;
  const control::TrajectoryPoint start = trajectory.Evaluate(t0);
  const control::FlatnessResult start_flat = control::ComputeFlatnessOutputs(start, vehicle);
  ASSERT_TRUE(start_flat.ok()) << start_flat;
  control::QuadState initial;
  initial.t_s = t0;
  initial.p_WB = start.p_W;
  initial.v_W = start.v_W;
  initial.q_WB = start_flat.q_WB;
  initial.omega_B = start_flat.omega_B;
  QuadrotorDynamics quad(params, initial);

  // Inputs sampled at the middle of each held step: the midpoint rule makes the zero-order hold
  // second-order accurate in the step (an end-point sample would be a 0.5 ms delay, ~mm in 1 s).
  // Rotor thrusts within the thrust range are asserted, so no saturation hides a mismatch.
  const double h = 1e-3;
  double max_position_error_m = 0.0, max_attitude_error_rad = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double t_mid = t0 + (k + 0.5) * h;
    const control::FlatnessResult flat = control::ComputeFlatnessOutputs(trajectory.Evaluate(t_mid), vehicle);
    ASSERT_TRUE(flat.ok()) << flat;
    control::RotorThrustCommand command;
    command.thrust_N = MixExactly(flat.thrust_command_mps2, flat.tau_B_Nm, vehicle);
    ASSERT_TRUE((command.thrust_N.array() > vehicle.rotor.MinThrust()).all() &&
                (command.thrust_N.array() < vehicle.rotor.MaxThrust()).all())
        << "reference needs saturated rotors: " << command.thrust_N.transpose();
    quad.SetRotorThrustCommand(command);
    quad.Step(h);
    const control::TrajectoryPoint reference = trajectory.Evaluate(t0 + (k + 1) * h);
    const control::FlatnessResult reference_flat = control::ComputeFlatnessOutputs(reference, vehicle);
    max_position_error_m = std::max(max_position_error_m, (quad.state().p_WB - reference.p_W).norm());
    max_attitude_error_rad = std::max(
        max_attitude_error_rad, quad.state().q_WB.angularDistance(reference_flat.q_WB));
  }
  std::cout << GetParam().name << ": open-loop 1 s, max position error " << max_position_error_m * 1e3
            << " mm, max attitude error " << max_attitude_error_rad * 180.0 / M_PI << " deg\n";
  // The midpoint hold errs by O(h^2): ~1e-5 m and ~1e-5 rad here. 0.1 mm after 1 s of open-loop
  // flight (an unstable chain of integrators) leaves a 10x margin, while a wrong sign or frame in
  // either model shows up as decimetres and a missing drag term (k_h, A, B, d_z) as millimetres.
  EXPECT_LT(max_position_error_m, 1e-4);
  EXPECT_LT(max_attitude_error_rad, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(
    Thesis, FlatnessRoundTripTest,
    ::testing::Values(
        // Accelerating along the circle during the smooth ramp-in (F.7.2 circle, 4 m/s).
        RoundTripCase{"circle_ramp", std::make_shared<control::CircleTrajectory>(), 1.0},
        // Full-speed lemniscate: changing curvature, torques on all axes.
        RoundTripCase{"lemniscate", std::make_shared<control::LemniscateTrajectory>(), 4.0},
        // Rest-to-rest 12 m/s^2 back-and-forth segment (G.6.2): large pitch and thrust changes.
        RoundTripCase{"back_and_forth", std::make_shared<control::BackAndForthTrajectory>(), 0.3}),
    [](const ::testing::TestParamInfo<RoundTripCase>& info) { return info.param.name; });

}  // namespace
}  // namespace aperture::sim
