#pragma once
// Thrust mixing: desired body torques eta_des_B [N m] and mass-normalized collective thrust
// c_des [m/s^2] -> four single-rotor thrusts [N] (Faessler thesis, Appendix G).
//
//  - Iterative mixer (G.4): start from equal thrusts m c / 4 (G.13), then alternate
//    i) kappa_i = kappa(f_i) (G.5) and ii) solving (G.1), (G.2) for f_i, until the yaw torque that
//    the thrusts produce with kappa(f_i) matches eta_z,des within `yaw_torque_tolerance_Nm`.
//  - One-shot mixer (baseline of Table G.2): a single solve with one constant kappa.
//  - Prioritized saturation (Algorithm 4, G.5): give up yaw torque first (down to an optional
//    assured magnitude), then collective thrust, then clip. Plain clipping as the baseline.
//
// Rotor fitness (G.2 text): true thrust f_i = gamma_i * (load-cell thrust of G.3), so rotor i's
// thrust range is gamma_i [f(u_min), f(u_max)] and its drag-torque coefficient is evaluated at
// its command's operating point, kappa_i = kappa(f_i / gamma_i) (kappa(f_i) of (G.1) when
// gamma_i = 1). RotorThrustCommand carries true thrusts; MotorCommandsFromRotorThrusts gives the
// motor commands u_i = rotor.CommandFromThrust(f_i / gamma_i).
//
// Solving (G.1), (G.2) for given kappa_i: the rows of roll, pitch and collective thrust are
// orthogonal with the yaw direction s = (+1, -1, +1, -1) (RotorYawSign), so f = f0 + t s with f0
// fixed by (eta_x, eta_y, c) and t = (eta_z - sum_i s_i kappa_i f0_i) / sum_i kappa_i. Moving
// along s changes only the yaw torque, shifting all thrusts equally only the collective thrust
// (and eta_z through kappa): Algorithm 4 is a line search along these two directions.
#include <Eigen/Core>
#include <ostream>

#include "control/commands.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

struct MixerParameters {
  enum class Mixing { kIterative, kOneShot };
  enum class Saturation { kPrioritized, kClip };
  Mixing mixing = Mixing::kIterative;
  Saturation saturation = Saturation::kPrioritized;
  // Iterative mixer: stop when |eta_z(f, kappa(f)) - eta_z,des| <= this. 1e-12 N m is ~1e-9 of a
  // typical yaw torque (1e-3 N m) and reached in 3-5 iterations with the default rotor model.
  double yaw_torque_tolerance_Nm = 1e-12;
  int max_iterations = 20;
  // eta_z,assured of Algorithm 4 [N m]: yaw saturation never reduces |eta_z| below it (0: off).
  double assured_yaw_torque_Nm = 0.0;
  // kappa of the one-shot mixer [m]; <= 0 selects kappa(m g / 4), the hover value (Table A.2's
  // constant 0.0195 m for the default rotor).
  double one_shot_torque_coefficient_m = 0.0;
};

struct MixerResult {
  RotorThrustCommand command;         // true thrusts, within each rotor's limits
  int iterations = 0;                 // number of (G.1)/(G.2) solves
  bool converged = true;              // iterative mixer met the tolerance (always true one-shot)
  bool yaw_torque_saturated = false;  // Algorithm 4 changed eta_z
  bool collective_thrust_saturated = false;  // Algorithm 4 shifted all thrusts
  bool clipped = false;                      // some thrust was clipped to its limit
  // Wrench the returned thrusts produce under (G.1), (G.2) with kappa_i of the rotor model.
  Eigen::Vector3d applied_torque_B = Eigen::Vector3d::Zero();  // [N m]
  double applied_collective_thrust_mps2 = 0.0;
};

std::ostream& operator<<(std::ostream& os, const MixerResult& result);

// kappa_i at true thrust f_i [m]: kappa(f_i / gamma_i) of (G.5).
double RotorTorqueCoefficient(const VehicleParameters& vehicle, int rotor_index, double thrust_N);
// (G.1): body torques [N m] of four true rotor thrusts, with kappa_i from RotorTorqueCoefficient.
Eigen::Vector3d BodyTorqueFromRotorThrusts(const VehicleParameters& vehicle,
                                           const Eigen::Vector4d& thrust_N);
// Motor commands u_i = CommandFromThrust(f_i / gamma_i) (inverse of G.3) that produce true
// thrusts f_i, clamped to [command_min, command_max]. This is what drives
// sim::QuadrotorDynamics::SetMotorCommands; its SetRotorThrustCommand instead expects load-cell
// thrusts f_i / gamma_i (a flight controller that does not know gamma_i).
Eigen::Vector4d MotorCommandsFromRotorThrusts(const VehicleParameters& vehicle,
                                              const Eigen::Vector4d& thrust_N);
// (G.2): mass-normalized collective thrust [m/s^2].
double CollectiveThrustFromRotorThrusts(const VehicleParameters& vehicle,
                                        const Eigen::Vector4d& thrust_N);

class Mixer {
 public:
  // Throws std::invalid_argument (from VehicleParameters::Validate, or naming the MixerParameters
  // field) for non-physical vehicles, max_iterations < 1 or negative tolerances / assured torque.
  explicit Mixer(const VehicleParameters& vehicle, const MixerParameters& params = {});

  // Throws std::invalid_argument when an input is not finite.
  MixerResult Mix(const Eigen::Vector3d& torque_des_B, double collective_thrust_des_mps2) const;

  const Eigen::Vector4d& min_thrust_N() const { return min_thrust_N_; }
  const Eigen::Vector4d& max_thrust_N() const { return max_thrust_N_; }
  const MixerParameters& params() const { return params_; }

 private:
  // Thrusts with eta_x, eta_y, c fixed (f0) and yaw torque eta_z, iterating on kappa(f) from
  // `kappa` (updated to kappa at the returned thrusts); adds the solves to `result`.
  Eigen::Vector4d SolveIterative(const Eigen::Vector4d& f0, double yaw_torque_Nm,
                                 Eigen::Vector4d& kappa, MixerResult& result) const;
  Eigen::Vector4d TorqueCoefficients(const Eigen::Vector4d& thrust_N) const;
  void SaturatePrioritized(const Eigen::Vector4d& f0, double yaw_torque_des_Nm,
                           Eigen::Vector4d& thrust_N, MixerResult& result) const;

  VehicleParameters vehicle_;
  MixerParameters params_;
  double half_sqrt2_arm_m_ = 0.0;  // sqrt(2)/2 l of (G.1)
  double one_shot_kappa_m_ = 0.0;
  Eigen::Vector4d min_thrust_N_, max_thrust_N_;
};

}  // namespace aperture::control
