#include "control/lqr_body_rate_controller.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "control/constants.h"
#include "control/proportional_body_rate_controller.h"

namespace aperture::control {
namespace {

// Body-rate plant of the design: rigid body (G.6) with the coupling term, torques following the
// commanded torque through the first-order lag (G.8) with alpha = (alpha_up + alpha_dwn) / 2.
// The controller runs at 1 kHz (zero-order hold); the lag is integrated exactly and the rates
// with 10 semi-implicit Euler sub-steps per control period.
struct BodyRatePlant {
  Eigen::Matrix3d J;
  double alpha_s;
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_B = Eigen::Vector3d::Zero();

  void Step(const Eigen::Vector3d& torque_des_B, double dt_s) {
    constexpr int kSubsteps = 10;
    const double h = dt_s / kSubsteps;
    const double decay = std::exp(-h / alpha_s);
    for (int k = 0; k < kSubsteps; ++k) {
      torque_B = torque_des_B + (torque_B - torque_des_B) * decay;
      omega_B += h * J.inverse() * (torque_B - omega_B.cross(J * omega_B));
    }
  }
};

constexpr double kBodyRateDt_s = 1e-3;

using TorqueLaw = std::function<Eigen::Vector3d(const ThrustRatesCommand&, const BodyRatePlant&)>;
using Reference = std::function<ThrustRatesCommand(double)>;

// Integral of |omega_des - omega| summed over the axes [rad]; also the largest overshoot of
// omega_x past a positive step (for step references) [rad/s].
struct Tracking {
  double integral_abs_error = 0.0;
  double max_omega_x = -1e9;
  Eigen::Vector3d final_error = Eigen::Vector3d::Zero();
};

Tracking SimulateBodyRateLoop(const TorqueLaw& law, const Reference& reference, double duration_s) {
  const VehicleParameters vehicle;
  BodyRatePlant plant{vehicle.Inertia(), BuildBodyRateLinearModel(vehicle).time_constant_s};
  Tracking tracking;
  for (double t = 0.0; t < duration_s; t += kBodyRateDt_s) {
    const ThrustRatesCommand command = reference(t);
    plant.Step(law(command, plant), kBodyRateDt_s);
    const ThrustRatesCommand next = reference(t + kBodyRateDt_s);
    tracking.final_error = next.omega_des_B - plant.omega_B;
    tracking.integral_abs_error += kBodyRateDt_s * tracking.final_error.cwiseAbs().sum();
    tracking.max_omega_x = std::max(tracking.max_omega_x, plant.omega_B.x());
  }
  return tracking;
}

ThrustRatesCommand StepReference(double /*t*/) {
  ThrustRatesCommand command;
  command.omega_des_B = Eigen::Vector3d(3.0, -2.0, 1.5);
  return command;
}

TorqueLaw Lqr(const LqrBodyRateController& controller) {
  return [&controller](const ThrustRatesCommand& c, const BodyRatePlant& plant) {
    return controller.ComputeTorque(c, plant.omega_B, plant.torque_B);
  };
}

TorqueLaw Proportional(const ProportionalBodyRateController& controller) {
  return [&controller](const ThrustRatesCommand& c, const BodyRatePlant& plant) {
    return controller.ComputeTorque(c.omega_des_B, plant.omega_B);
  };
}

TEST(LqrBodyRateController, GainsEquivalentToHighGainProportional) {
  const VehicleParameters vehicle;
  const LqrBodyRateController lqr(vehicle);
  ASSERT_TRUE(lqr.care_result().ok()) << lqr.care_result();
  const Eigen::Vector3d p_high = ProportionalBodyRateParameters::HighGain().rate_gains_per_s;
  const double alpha =
      0.5 * (vehicle.rotor.time_constant_up_s + vehicle.rotor.time_constant_down_s);
  EXPECT_DOUBLE_EQ(lqr.model().time_constant_s, alpha);
  for (int i = 0; i < 3; ++i) {
    // (G.11): the rate gain equals J p of controller (b) (G.6.2).
    const double k_omega = vehicle.inertia_diag_kgm2[i] * p_high[i];
    EXPECT_NEAR(lqr.gain()(i, i), k_omega, 1e-10 * k_omega);
    EXPECT_NEAR(lqr.gain()(i, 3 + i), std::sqrt(1.0 + 2.0 * alpha * p_high[i]) - 1.0, 1e-9);
  }
  // The helper reproduces the documented defaults for the Table A.2 inertia.
  const LqrBodyRateParameters from_gains =
      LqrBodyRateParameters::FromEquivalentRateGains(vehicle.inertia_diag_kgm2, p_high);
  EXPECT_TRUE(from_gains.state_weights.isApprox(LqrBodyRateParameters().state_weights, 1e-12));
}

TEST(LqrBodyRateController, RejectsWeightsWithoutStabilizingGain) {
  LqrBodyRateParameters params;
  params.state_weights[1] = 0.0;  // the pitch-rate integrator is then unobservable in the cost
  EXPECT_THROW(LqrBodyRateController(VehicleParameters(), params), std::invalid_argument);
  params = LqrBodyRateParameters();
  params.input_weights[0] = 0.0;
  EXPECT_THROW(LqrBodyRateController(VehicleParameters(), params), std::invalid_argument);
}

TEST(LqrBodyRateController, TracksRateStepBetterThanProportionalControllers) {
  const VehicleParameters vehicle;
  const LqrBodyRateController lqr(vehicle);
  const ProportionalBodyRateController low(vehicle, ProportionalBodyRateParameters::LowGain());
  const ProportionalBodyRateController high(vehicle, ProportionalBodyRateParameters::HighGain());
  const Tracking t_lqr = SimulateBodyRateLoop(Lqr(lqr), StepReference, 0.6);
  const Tracking t_low = SimulateBodyRateLoop(Proportional(low), StepReference, 0.6);
  const Tracking t_high = SimulateBodyRateLoop(Proportional(high), StepReference, 0.6);
  // Table G.1: the LQR tracks much better than the low-gain P controller (a) ...
  EXPECT_LT(t_lqr.integral_abs_error, 0.7 * t_low.integral_abs_error)
      << "LQR " << t_lqr.integral_abs_error << " low-gain P " << t_low.integral_abs_error;
  // ... and, with the same rate gain as (b), does not ring like it: the high-gain P loop has
  // damping 0.36 (~30 % overshoot), the LQR 0.79 (~2 %).
  const double overshoot_lqr = t_lqr.max_omega_x / 3.0 - 1.0;
  const double overshoot_high = t_high.max_omega_x / 3.0 - 1.0;
  EXPECT_GT(overshoot_high, 0.2);
  EXPECT_LT(overshoot_lqr, 0.05);
  EXPECT_LT(t_lqr.final_error.norm(), 1e-3);
}

TEST(LqrBodyRateController, ZeroSteadyStateErrorWithGyroscopicCoupling) {
  // A constant multi-axis rate needs the torque omega x J omega: the feedback linearization and
  // eta_ref of (G.12) supply it, so the error vanishes (it would not with a wrong eta_ref).
  const LqrBodyRateController lqr{VehicleParameters()};
  auto reference = [](double) {
    ThrustRatesCommand command;
    command.omega_des_B = Eigen::Vector3d(4.0, -5.0, 6.0);
    return command;
  };
  const Tracking tracking = SimulateBodyRateLoop(Lqr(lqr), reference, 1.0);
  // Closed-loop poles at <= -20 1/s: after 1 s the transient is below 1e-8 of the step.
  EXPECT_LT(tracking.final_error.norm(), 1e-6);
}

TEST(LqrBodyRateController, AngularAccelerationFeedForwardReducesTrackingError) {
  const LqrBodyRateController lqr{VehicleParameters()};
  const double amplitude = 4.0, frequency_hz = 3.0;
  auto reference = [&](double t, bool feed_forward) {
    ThrustRatesCommand command;
    const double w = 2.0 * kPi * frequency_hz;
    command.omega_des_B =
        Eigen::Vector3d(amplitude * std::sin(w * t), 0.0, 0.5 * amplitude * std::cos(w * t));
    if (feed_forward) {
      command.omega_dot_des_B = Eigen::Vector3d(amplitude * w * std::cos(w * t), 0.0,
                                                -0.5 * amplitude * w * std::sin(w * t));
    }
    return command;
  };
  const Tracking with = SimulateBodyRateLoop(
      Lqr(lqr), [&](double t) { return reference(t, true); }, 1.0);
  const Tracking without = SimulateBodyRateLoop(
      Lqr(lqr), [&](double t) { return reference(t, false); }, 1.0);
  EXPECT_LT(with.integral_abs_error, 0.5 * without.integral_abs_error)
      << with.integral_abs_error << " vs " << without.integral_abs_error;
}

TEST(ProportionalBodyRateController, ImplementsB21) {
  const VehicleParameters vehicle;
  const ProportionalBodyRateController controller(vehicle);
  const Eigen::Vector3d omega_des(1.0, -2.0, 0.5), omega(0.5, 0.5, -1.0);
  const Eigen::Matrix3d J = vehicle.Inertia();
  // Table A.2 gains written out: J diag(33.3, 33.3, 6.7) e + omega x J omega.
  const Eigen::Vector3d expected =
      J * Eigen::Vector3d(33.3 * 0.5, 33.3 * -2.5, 6.7 * 1.5) + omega.cross(J * omega);
  EXPECT_TRUE(controller.ComputeTorque(omega_des, omega).isApprox(expected, 1e-14));
  ProportionalBodyRateParameters bad;
  bad.rate_gains_per_s.x() = -1.0;
  EXPECT_THROW(ProportionalBodyRateController(vehicle, bad), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
