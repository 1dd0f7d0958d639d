#pragma once
// Physical parameters of the quadrotor shared by the control stack (which models the vehicle)
// and the simulator (which is the vehicle). Defaults follow the thesis platforms: mass, inertia,
// arm length and rotor torque coefficient from Table A.2; motor time constants from G.6.1;
// rotor-drag coefficients of the F.7.3 identification. The thesis gives no coefficients of the
// thrust and torque polynomials (G.3, G.4): those below are synthetic, chosen to match Table A.2
// at hover (see RotorParameters). Units SI.
//
// Rotor numbering and geometry follow thesis (G.1): X configuration, rotor i at
// (x, y) = l/sqrt(2) * {(+,+), (+,-), (-,-), (-,+)} in B; rotors 1 and 3 produce positive yaw
// torque (kappa_i f_i), rotors 2 and 4 negative.
#include <Eigen/Core>

namespace aperture::control {

// Single rotor: thrust and drag torque as quadratics of the motor command u in [-1, 1]
// (G.3, G.4), first-order thrust dynamics with separate up/down time constants (G.7).
struct RotorParameters {
  // f(u) = k2 u^2 + k1 u + k0 [N]. Chosen so f(-1) = 0.05 N (idle) and f(1) = 3.25 N: a 0.45 kg
  // vehicle hovers at u ~ 0.11 with a thrust-to-weight ratio of ~2.9.
  Eigen::Vector3d thrust_coeffs_N{0.9, 1.6, 0.75};  // {k0, k1, k2}
  // tau(u) = k2 u^2 + k1 u + k0 [N m]. Chosen so kappa(f) = tau/f is 0.0195 m at hover (Table A.2)
  // and falls by about 10 % over the command range (0.0207 m at f = 0.12 N to 0.0189 m at full
  // thrust), the trend of Fig. G.4: a least-squares fit of that kappa(f) times f(u).
  Eigen::Vector3d torque_coeffs_Nm{0.017769, 0.030269, 0.013248};  // {k0, k1, k2}
  double time_constant_up_s = 0.011;    // alpha_up (G.6.1)
  double time_constant_down_s = 0.027;  // alpha_dwn (G.6.1)
  double command_min = -1.0;
  double command_max = 1.0;

  double ThrustFromCommand(double u) const;       // (G.3)
  double DragTorqueFromCommand(double u) const;   // (G.4)
  // Inverse of (G.3) on the rising branch; f is clamped to [f(command_min), f(command_max)].
  double CommandFromThrust(double f_N) const;
  double MinThrust() const { return ThrustFromCommand(command_min); }
  double MaxThrust() const { return ThrustFromCommand(command_max); }
  // kappa(f) of (G.5): drag torque over thrust at the command that produces f [m]; outside
  // [MinThrust, MaxThrust] the value at the nearest limit.
  double TorqueCoefficient(double f_N) const;
};

struct VehicleParameters {
  double mass_kg = 0.45;                                                // Table A.2
  Eigen::Vector3d inertia_diag_kgm2{0.001, 0.001, 0.002};               // Table A.2
  double arm_length_m = 0.178;                                          // Table A.2
  double gravity_mps2 = 9.81;
  // Mass-normalized rotor-drag coefficients D = diag(dx, dy, dz) of (F.2) [1/s]. F.7.3
  // identified dx = 0.544, dy = 0.386 on the circle and 0.491, 0.236 on the lemniscate; the
  // defaults are rounded values in that range (aperture bench control uses them); dz = 0 as there.
  Eigen::Vector3d rotor_drag_D_per_s{0.5, 0.35, 0.0};
  // Drag-induced torque terms of (F.4) [N m s/m] and [N m s/rad]; zero by default as in F.7.
  Eigen::Matrix3d rotor_drag_A = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotor_drag_B = Eigen::Matrix3d::Zero();
  double thrust_velocity_coeff_kh = 0.0;  // k_h of (F.5) [1/m]
  RotorParameters rotor;
  // Rotor fitness factors gamma_i: true thrust = gamma_i * thrust of (G.3) (G.2 text).
  Eigen::Vector4d rotor_fitness{1.0, 1.0, 1.0, 1.0};

  Eigen::Matrix3d Inertia() const { return inertia_diag_kgm2.asDiagonal(); }
  // Position of rotor i (0-based) in B, in the plane z = 0 [m].
  Eigen::Vector3d RotorPosition_B(int i) const;
  // Sign of rotor i's drag torque about z_B: +1 for rotors 1 and 3, -1 for 2 and 4 (G.1).
  static double RotorYawSign(int i) { return (i % 2 == 0) ? 1.0 : -1.0; }
  // Throws std::invalid_argument naming the field when a value is non-physical
  // (mass or inertia <= 0, non-finite numbers, thrust map not increasing on the command range).
  void Validate() const;
};

}  // namespace aperture::control
