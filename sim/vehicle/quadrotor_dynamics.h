#pragma once
// Simulated quadrotor: the rigid body with rotor drag of Faessler thesis (F.1)-(F.5), driven by
// four rotors whose thrust follows the first-order lag (G.7) of the thrust map (G.3), with drag
// torques from (G.4) and body torques from the geometry of (G.1). Frames and units: DESIGN.md
// (W world z up, B body x forward / z up), SI.
//
// State: the control::QuadState {p_WB, v_W, q_WB, omega_B} plus, per rotor, the load-cell thrust
// f_check_i of (G.3)/(G.7), i.e. the thrust the rotor would produce with fitness 1. The lag acts on
// this thrust, as in the thesis (G.7), not on the motor command; the true thrust is
// f_i = gamma_i * f_check_i (G.2 text) and the drag torque is gamma_i * tau(u_eff_i), where u_eff_i
// is the command that produces f_check_i through (G.3): a weak rotor loses torque in proportion to
// thrust, so tau/f stays kappa(f) of (G.5).
//
// Inputs, held constant over each Step():
//   * motor commands u_i (clamped to [command_min, command_max]) or desired rotor thrusts, mapped
//     to commands with the inverse of (G.3) as a flight controller would (it does not know gamma_i:
//     commanding f / gamma_i yields f);
//   * wind velocity v_wind_W: drag (F.2), (F.4) and the k_h term of (F.5) use the airspeed
//     v_W - v_wind_W;
//   * an external force (W) and torque (B), and instantaneous impulses, for disturbances.
//
// Model (with v_a = v_W - v_wind_W, R = R_WB):
//   p' = v                                                               (F.1)
//   v' = -g z_W + c z_B - R D R^T v_a + F_ext / m                        (F.2)
//   c  = sum_i f_i / m + k_h v_h^2,  v_h = v_a^T (x_B + y_B)            (F.5)
//   R' = R [omega]x                                                      (F.3)
//   J omega' = eta - omega x J omega - A R^T v_a - B omega + tau_ext     (F.4), tau_g = 0
//   eta = sum_i r_i x (0, 0, f_i) + sum_i s_i gamma_i tau(u_eff_i) z_B   (G.1), s_i = RotorYawSign
//   f_check_i' = (f(u_i) - f_check_i) / alpha_{up|dwn}                   (G.7)
// Integration: classic RK4 with a fixed step (default 1 ms); (G.7) is solved exactly inside each
// step (the thrust never crosses its target, so the up/down branch is constant over a step) and
// its closed form is evaluated at the RK4 stage times. q_WB is renormalized after every step.
//
// Typical SITL loop (sim/vehicle/disturbances.h, sim/sensors/imu_sensor.h):
//   QuadrotorDynamics vehicle(params, initial_state);
//   for (;;) {
//     vehicle.SetRotorThrustCommand(mixer_output);        // or SetMotorCommands(u)
//     disturbances.StepVehicle(0.001, &vehicle);          // or vehicle.Step(0.001)
//     for (const auto& sample : imu.Update(vehicle.state().t_s, vehicle.SpecificForce_B(),
//                                          vehicle.state().omega_B)) { autopilot(sample); }
//   }
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "control/commands.h"
#include "control/quad_state.h"
#include "control/vehicle_parameters.h"

namespace aperture::sim {

struct QuadrotorDynamicsParams {
  control::VehicleParameters vehicle;  // thesis defaults (Table A.2, G.6.1)
  // Largest RK4 step [s]; Step(dt) is split into equal sub-steps no longer than this. 1 ms
  // resolves the 11 ms rotor time constant (step error of RK4 ~ (h/tau)^5) and body dynamics.
  double max_integration_step_s = 0.001;
  // false: every rotor produces f(u) the moment u is set, (G.7) is bypassed. For comparisons with
  // models that assume instantaneous thrust (flatness, F.1-F.5); a tiny time constant is not the
  // same, since RK4 samples the thrust at the start of a step, before such a fast lag has moved.
  bool rotor_lag_enabled = true;
  // Ground plane z_W = ground_height_m with landing gear (off by default: the plain model F.1-F.5).
  // After each RK4 step, a vehicle whose origin of B is at or below the gear height above the
  // plane and not climbing is put to rest on its gear: p_z = ground + landing_gear_height_m,
  // v = 0, omega = 0, roll and pitch removed (yaw kept) -- an inelastic touchdown on gear that
  // keeps it upright, with static friction. It lifts off once the thrust exceeds its weight.
  // While resting, the specific force is the ground reaction R^T g z_W. Crashes (tip-over,
  // bounce) are not modelled; last_touchdown_speed_mps() / last_touchdown_tilt_rad() let a caller
  // judge them (the SITL does: sim/sitl/collision_checker.h). In the SITL this ground plane is
  // also the collision checker's.
  bool ground_contact_enabled = false;
  double ground_height_m = 0.0;
  // Height of the origin of B above the ground when resting on the gear [m]; >= 0. The SITL needs
  // it above the collision body sphere's radius (else resting is a crash).
  double landing_gear_height_m = 0.0;
  // Effects beyond (F.2)-(F.5) that the controllers do not model; zero by default (the vehicle is
  // then the controllers' model). The mismatched bench vehicle sets them (sim/sitl/
  // vehicle_mismatch.h):
  //  * parasitic (fuselage) drag: -c_q |v_a| v_a is added to v' of (F.2), c_q mass-normalized
  //    [1/m];
  //  * thrust-dependent rotor drag: D of (F.2) is scaled by (sum_i f_i / (m g))^e, 1 in hover;
  //    e = 0.5 is drag in proportion to rotor speed, the dependence F.7.4 names as not modelled;
  //  * battery sag: every rotor's thrust map (G.3) is scaled by max(0, 1 - s t) at time t [1/s]
  //    (the drag torque follows, through the effective command of (G.4)).
  double quadratic_drag_per_m = 0.0;
  double drag_thrust_exponent = 0.0;
  double battery_sag_per_s = 0.0;

  // Throws std::invalid_argument naming the field (delegates to VehicleParameters::Validate;
  // negative drag terms or sag, an exponent outside [0, 2]), and when the lag is enabled but a
  // rotor time constant is shorter than max_integration_step_s.
  void Validate() const;
};

class QuadrotorDynamics {
 public:
  // Starts at `initial` with all rotors at the minimum command, thrust settled at MinThrust().
  // Throws std::invalid_argument for invalid params or a non-finite / non-unit-quaternion state.
  explicit QuadrotorDynamics(const QuadrotorDynamicsParams& params,
                             const control::QuadState& initial = control::QuadState());

  // Motor commands u_i in the numbering of (G.1); clamped to the command limits.
  void SetMotorCommands(const Eigen::Vector4d& u);
  // Desired thrusts, converted to commands with the inverse of (G.3) (clamped to the thrust range).
  void SetRotorThrustCommand(const control::RotorThrustCommand& command);
  // Sets every rotor's thrust to the steady state of its current command (no transient), e.g. to
  // start in hover.
  void SettleRotors();

  void SetWindVelocity_W(const Eigen::Vector3d& wind_W) { wind_W_ = wind_W; }
  void SetExternalForce_W(const Eigen::Vector3d& force_W_N) { external_force_W_ = force_W_N; }
  void SetExternalTorque_B(const Eigen::Vector3d& torque_B_Nm) { external_torque_B_ = torque_B_Nm; }
  // Instantaneous push: v_W += impulse_W / m, omega_B += J^-1 angular_impulse_B.
  void ApplyImpulse(const Eigen::Vector3d& impulse_W_Ns,
                    const Eigen::Vector3d& angular_impulse_B_Nms = Eigen::Vector3d::Zero());

  // Advances the state by dt_s > 0 (throws std::invalid_argument otherwise) with inputs held.
  void Step(double dt_s);

  // Replaces the rigid-body state (rotors unchanged; with ground contact, a state at or below the
  // ground and not climbing is put to rest on it); throws like the constructor.
  void SetState(const control::QuadState& state);
  const control::QuadState& state() const { return state_; }
  const QuadrotorDynamicsParams& params() const { return params_; }
  const Eigen::Vector4d& motor_commands() const { return commands_; }
  const Eigen::Vector3d& wind_W() const { return wind_W_; }

  // True rotor thrusts f_i = gamma_i * f_check_i [N].
  Eigen::Vector4d RotorThrusts_N() const;
  // Commands that would produce the current thrusts in steady state (argument of (G.4)).
  Eigen::Vector4d EffectiveMotorCommands() const;
  // True while resting on the ground plane (ground_contact_enabled only).
  bool on_ground() const { return on_ground_; }
  // |v_W| at the most recent touchdown, 0 before the first (and for a state set on the ground)
  // [m/s].
  double last_touchdown_speed_mps() const { return last_touchdown_speed_mps_; }
  // Angle between z_B and z_W at the most recent touchdown, before the gear levelled it [rad].
  double last_touchdown_tilt_rad() const { return last_touchdown_tilt_rad_; }

  // Mass-normalized collective thrust c of (F.5) at the current state [m/s^2].
  double CollectiveThrust_mps2() const;
  // Body torque eta of (G.1) from the rotors only (no drag torques of F.4, no external) [N m].
  Eigen::Vector3d RotorTorque_B() const;
  // What an ideal accelerometer at the centre of mass reads: all non-gravitational forces over
  // mass, in B: c z_B - D R^T v_a + R^T F_ext / m [m/s^2]; resting on the ground, R^T g z_W.
  // Impulses (Dirac forces) are not seen.
  Eigen::Vector3d SpecificForce_B() const;
  // Linear acceleration v' of (F.2) at the current state (0 while resting on the ground) [m/s^2].
  Eigen::Vector3d Acceleration_W() const;

 private:
  struct RigidBody {
    Eigen::Vector3d p_W, v_W;
    Eigen::Vector4d q_wxyz;  // q_WB as a plain 4-vector so RK4 can add stages
    Eigen::Vector3d omega_B;
  };
  struct Derivative {
    Eigen::Vector3d p_dot, v_dot;
    Eigen::Vector4d q_dot;
    Eigen::Vector3d omega_dot;
  };
  struct Forces {
    double collective_thrust_mps2;
    Eigen::Vector3d specific_force_B;  // c z_B - D R^T v_a + R^T F_ext / m
    Eigen::Vector3d torque_B;  // all torques of (F.4) right-hand side except omega x J omega
  };

  Forces ComputeForces(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_W,
                       const Eigen::Vector3d& omega_B, const Eigen::Vector4d& f_check_N) const;
  Eigen::Vector3d RotorTorqueFor(const Eigen::Vector4d& f_check_N) const;
  Derivative ComputeDerivative(const RigidBody& x, const Eigen::Vector4d& f_check_N) const;
  // Closed-form solution of (G.7) after `elapsed_s` from f_check_start.
  Eigen::Vector4d RotorThrustsAfter(const Eigen::Vector4d& f_check_start, double elapsed_s) const;
  // Steady-state load-cell thrust of command u at the current time: (G.3) with the battery sag.
  double TargetThrust(double u) const;
  void StepRk4(double h_s);
  void ResolveGroundContact();
  // Specific force of the free vehicle (no ground reaction) at the current state, in B.
  Eigen::Vector3d FreeSpecificForce_B() const;

  QuadrotorDynamicsParams params_;
  control::QuadState state_;
  Eigen::Vector4d commands_;
  Eigen::Vector4d f_check_N_;  // lagged load-cell thrusts (state of G.7)
  Eigen::Vector3d wind_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d external_force_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d external_torque_B_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_, inertia_inverse_;
  Eigen::Matrix<double, 3, 4> rotor_positions_B_;
  bool on_ground_ = false;
  double last_touchdown_speed_mps_ = 0.0;
  double last_touchdown_tilt_rad_ = 0.0;
};

}  // namespace aperture::sim
