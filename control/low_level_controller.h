#pragma once
// The flight-controller side of the control stack (DESIGN.md data flow, Faessler thesis App. G):
// one call per low-level control period turns the high-level ThrustRatesCommand and the gyro
// rates into rotor thrusts and motor commands:
//   body-rate law (LQR (G.12) with eta_hat, or the P baseline (B.21))
//   -> mixer (iterative G.4 or one-shot; prioritized saturation Algorithm 4 or clipping)
//   -> RotorThrustEstimator propagated with the thrusts actually commanded (G.7),
//      giving eta_hat for the next period.
// Optionally (beyond the thesis) a TorqueDisturbanceObserver estimates the torque d_hat that
// eta_hat does not explain (a weak rotor, map errors); the LQR then feeds back eta_hat + d_hat as
// the body torque and both laws subtract d_hat from their output, which removes the steady rate
// error a constant disturbance leaves (integral action).
#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "control/commands.h"
#include "control/lqr_body_rate_controller.h"
#include "control/mixer.h"
#include "control/proportional_body_rate_controller.h"
#include "control/rotor_thrust_estimator.h"
#include "control/torque_disturbance_observer.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

struct LowLevelControllerParameters {
  enum class BodyRateLaw { kLqr, kProportional };
  BodyRateLaw body_rate_law = BodyRateLaw::kLqr;  // the thesis' proposal
  LqrBodyRateParameters lqr;                      // used with kLqr
  ProportionalBodyRateParameters proportional;    // used with kProportional (low gain)
  MixerParameters mixer;
  // Time constant of the torque-disturbance observer [s]; 0: off (the thesis' laws).
  double torque_observer_time_constant_s = 0.0;
  // Throws std::invalid_argument naming the field (a negative or non-finite time constant).
  // Inline: the scenario loader checks it without linking the controller.
  void Validate() const {
    if (!(std::isfinite(torque_observer_time_constant_s) &&
          torque_observer_time_constant_s >= 0.0)) {
      throw std::invalid_argument(
          "LowLevelControllerParameters.torque_observer_time_constant_s must be finite and >= 0 "
          "(0: off)");
    }
  }
};

struct LowLevelOutput {
  Eigen::Vector3d torque_des_B = Eigen::Vector3d::Zero();    // body-rate law output [N m]
  Eigen::Vector3d torque_disturbance_B = Eigen::Vector3d::Zero();  // d_hat (0 when off) [N m]
  MixerResult mix;                                           // thrusts [N] and saturation report
  Eigen::Vector4d motor_commands = Eigen::Vector4d::Zero();  // u_i for the ESCs (inverse G.3)
};

class LowLevelController {
 public:
  // Throws std::invalid_argument for invalid vehicle or controller parameters.
  explicit LowLevelController(const VehicleParameters& vehicle,
                              const LowLevelControllerParameters& params = {});

  // One control period: omega_B are the gyro rates [rad/s]; the returned thrusts are meant to be
  // held for dt_s > 0 [s], over which the thrust estimate is propagated. Throws
  // std::invalid_argument for non-finite inputs or dt_s <= 0.
  LowLevelOutput Step(const ThrustRatesCommand& command, const Eigen::Vector3d& omega_B,
                      double dt_s);

  // Re-initializes the rotor thrust estimate (e.g. zeros for motors off on the ground) and forgets
  // the torque disturbance.
  void ResetThrustEstimate(const Eigen::Vector4d& thrust_N);
  const RotorThrustEstimator& estimator() const { return estimator_; }
  const LqrBodyRateController& lqr() const { return lqr_; }

 private:
  VehicleParameters vehicle_;
  LowLevelControllerParameters params_;
  LqrBodyRateController lqr_;
  ProportionalBodyRateController proportional_;
  Mixer mixer_;
  RotorThrustEstimator estimator_;
  std::optional<TorqueDisturbanceObserver> observer_;  // when the time constant is > 0
  double previous_dt_s_ = 0.0;
};

}  // namespace aperture::control
