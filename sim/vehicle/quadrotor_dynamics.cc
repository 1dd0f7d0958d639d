#include "sim/vehicle/quadrotor_dynamics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::sim {
namespace {

void RequireValidState(const control::QuadState& state) {
  if (!state.IsValid()) {
    throw std::invalid_argument(
        "QuadrotorDynamics: state must be finite with a unit quaternion q_WB (|1 - |q|| < 1e-6)");
  }
}

Eigen::Matrix3d RotationFromWxyz(const Eigen::Vector4d& q_wxyz) {
  return Eigen::Quaterniond(q_wxyz[0], q_wxyz[1], q_wxyz[2], q_wxyz[3])
      .normalized()
      .toRotationMatrix();
}

}  // namespace

void QuadrotorDynamicsParams::Validate() const {
  vehicle.Validate();
  if (!(std::isfinite(max_integration_step_s) && max_integration_step_s > 0.0)) {
    throw std::invalid_argument("QuadrotorDynamicsParams.max_integration_step_s must be > 0, got " +
                                std::to_string(max_integration_step_s));
  }
  if (!std::isfinite(ground_height_m)) {
    throw std::invalid_argument("QuadrotorDynamicsParams.ground_height_m must be finite");
  }
  if (!(std::isfinite(landing_gear_height_m) && landing_gear_height_m >= 0.0)) {
    throw std::invalid_argument(
        "QuadrotorDynamicsParams.landing_gear_height_m must be finite and >= 0, got " +
        std::to_string(landing_gear_height_m));
  }
  control::RequireNonNegative(quadratic_drag_per_m, "QuadrotorDynamicsParams.quadratic_drag_per_m");
  control::RequireInRange(drag_thrust_exponent, 0.0, 2.0,
                          "QuadrotorDynamicsParams.drag_thrust_exponent");
  control::RequireNonNegative(battery_sag_per_s, "QuadrotorDynamicsParams.battery_sag_per_s");
  const double fastest_lag_s =
      std::min(vehicle.rotor.time_constant_up_s, vehicle.rotor.time_constant_down_s);
  if (rotor_lag_enabled && fastest_lag_s < max_integration_step_s) {
    throw std::invalid_argument(
        "QuadrotorDynamicsParams: rotor time constant " + std::to_string(fastest_lag_s) +
        " s is shorter than max_integration_step_s " + std::to_string(max_integration_step_s) +
        " s; RK4 cannot resolve that lag: reduce the step or set rotor_lag_enabled = false");
  }
}

QuadrotorDynamics::QuadrotorDynamics(const QuadrotorDynamicsParams& params,
                                     const control::QuadState& initial)
    : params_(params) {
  params_.Validate();
  SetState(initial);
  const control::VehicleParameters& vehicle = params_.vehicle;
  inertia_ = vehicle.Inertia();
  inertia_inverse_ = inertia_.inverse();
  for (int i = 0; i < 4; ++i) rotor_positions_B_.col(i) = vehicle.RotorPosition_B(i);
  commands_.setConstant(vehicle.rotor.command_min);
  SettleRotors();
}

void QuadrotorDynamics::SetState(const control::QuadState& state) {
  RequireValidState(state);
  state_ = state;
  state_.q_WB.normalize();
  on_ground_ = false;
  ResolveGroundContact();
}

void QuadrotorDynamics::SetMotorCommands(const Eigen::Vector4d& u) {
  if (!u.allFinite()) {
    throw std::invalid_argument("QuadrotorDynamics::SetMotorCommands: commands must be finite");
  }
  const control::RotorParameters& rotor = params_.vehicle.rotor;
  commands_ = u.cwiseMax(rotor.command_min).cwiseMin(rotor.command_max);
  if (!params_.rotor_lag_enabled) SettleRotors();
}

void QuadrotorDynamics::SetRotorThrustCommand(const control::RotorThrustCommand& command) {
  if (!command.thrust_N.allFinite()) {
    throw std::invalid_argument("QuadrotorDynamics::SetRotorThrustCommand: thrusts must be finite");
  }
  Eigen::Vector4d u;
  for (int i = 0; i < 4; ++i) u[i] = params_.vehicle.rotor.CommandFromThrust(command.thrust_N[i]);
  SetMotorCommands(u);
}

double QuadrotorDynamics::TargetThrust(double u) const {
  const double f_N = params_.vehicle.rotor.ThrustFromCommand(u);
  if (params_.battery_sag_per_s == 0.0) return f_N;
  return std::max(0.0, 1.0 - params_.battery_sag_per_s * state_.t_s) * f_N;
}

void QuadrotorDynamics::SettleRotors() {
  for (int i = 0; i < 4; ++i) f_check_N_[i] = TargetThrust(commands_[i]);
}

void QuadrotorDynamics::ApplyImpulse(const Eigen::Vector3d& impulse_W_Ns,
                                     const Eigen::Vector3d& angular_impulse_B_Nms) {
  if (!(impulse_W_Ns.allFinite() && angular_impulse_B_Nms.allFinite())) {
    throw std::invalid_argument("QuadrotorDynamics::ApplyImpulse: impulses must be finite");
  }
  state_.v_W += impulse_W_Ns / params_.vehicle.mass_kg;
  state_.omega_B += inertia_inverse_ * angular_impulse_B_Nms;
}

Eigen::Vector4d QuadrotorDynamics::RotorThrusts_N() const {
  return params_.vehicle.rotor_fitness.cwiseProduct(f_check_N_);
}

Eigen::Vector4d QuadrotorDynamics::EffectiveMotorCommands() const {
  Eigen::Vector4d u;
  for (int i = 0; i < 4; ++i) u[i] = params_.vehicle.rotor.CommandFromThrust(f_check_N_[i]);
  return u;
}

QuadrotorDynamics::Forces QuadrotorDynamics::ComputeForces(const Eigen::Matrix3d& R_WB,
                                                           const Eigen::Vector3d& v_W,
                                                           const Eigen::Vector3d& omega_B,
                                                           const Eigen::Vector4d& f_check_N) const {
  const control::VehicleParameters& vehicle = params_.vehicle;
  const Eigen::Vector3d airspeed_B = R_WB.transpose() * (v_W - wind_W_);
  const Eigen::Vector4d f_N = vehicle.rotor_fitness.cwiseProduct(f_check_N);

  Forces forces;
  const double v_h = airspeed_B.x() + airspeed_B.y();  // v^T (x_B + y_B)
  forces.collective_thrust_mps2 =
      f_N.sum() / vehicle.mass_kg + vehicle.thrust_velocity_coeff_kh * v_h * v_h;  // (F.5)
  Eigen::Vector3d drag_D_per_s = vehicle.rotor_drag_D_per_s;
  if (params_.drag_thrust_exponent != 0.0) {
    const double hover_ratio = f_N.sum() / (vehicle.mass_kg * vehicle.gravity_mps2);
    drag_D_per_s *= std::pow(std::max(0.0, hover_ratio), params_.drag_thrust_exponent);
  }
  forces.specific_force_B = forces.collective_thrust_mps2 * Eigen::Vector3d::UnitZ() -
                            drag_D_per_s.cwiseProduct(airspeed_B) +  // (F.2)
                            R_WB.transpose() * external_force_W_ / vehicle.mass_kg;
  if (params_.quadratic_drag_per_m != 0.0) {
    forces.specific_force_B -= params_.quadratic_drag_per_m * airspeed_B.norm() * airspeed_B;
  }

  // (F.4) rotor-drag torques (tau_g = 0) and the external torque.
  forces.torque_B = RotorTorqueFor(f_check_N) - vehicle.rotor_drag_A * airspeed_B -
                    vehicle.rotor_drag_B * omega_B + external_torque_B_;
  return forces;
}

Eigen::Vector3d QuadrotorDynamics::RotorTorqueFor(const Eigen::Vector4d& f_check_N) const {
  // (G.1): arm moments of the thrusts and the rotors' drag torques about z_B.
  const control::VehicleParameters& vehicle = params_.vehicle;
  Eigen::Vector3d torque_B = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    const double f_N = vehicle.rotor_fitness[i] * f_check_N[i];
    const Eigen::Vector3d& r = rotor_positions_B_.col(i);
    torque_B += Eigen::Vector3d(r.y() * f_N, -r.x() * f_N, 0.0);
    const double u_eff = vehicle.rotor.CommandFromThrust(f_check_N[i]);
    torque_B.z() += control::VehicleParameters::RotorYawSign(i) * vehicle.rotor_fitness[i] *
                    vehicle.rotor.DragTorqueFromCommand(u_eff);
  }
  return torque_B;
}

Eigen::Vector3d QuadrotorDynamics::RotorTorque_B() const { return RotorTorqueFor(f_check_N_); }

double QuadrotorDynamics::CollectiveThrust_mps2() const {
  return ComputeForces(state_.q_WB.toRotationMatrix(), state_.v_W, state_.omega_B, f_check_N_)
      .collective_thrust_mps2;
}

Eigen::Vector3d QuadrotorDynamics::FreeSpecificForce_B() const {
  return ComputeForces(state_.q_WB.toRotationMatrix(), state_.v_W, state_.omega_B, f_check_N_)
      .specific_force_B;
}

Eigen::Vector3d QuadrotorDynamics::SpecificForce_B() const {
  if (on_ground_) {
    return state_.q_WB.conjugate() * (params_.vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ());
  }
  return FreeSpecificForce_B();
}

Eigen::Vector3d QuadrotorDynamics::Acceleration_W() const {
  return state_.q_WB * SpecificForce_B() - params_.vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ();
}

void QuadrotorDynamics::ResolveGroundContact() {
  if (!params_.ground_contact_enabled) return;
  const double rest_z_m = params_.ground_height_m + params_.landing_gear_height_m;
  if (state_.p_WB.z() > rest_z_m || state_.v_W.z() > 0.0) {
    on_ground_ = false;
    return;
  }
  if (!on_ground_) {
    last_touchdown_speed_mps_ = state_.v_W.norm();
    const Eigen::Vector3d z_B_W = state_.q_WB * Eigen::Vector3d::UnitZ();
    last_touchdown_tilt_rad_ = std::acos(std::clamp(z_B_W.z(), -1.0, 1.0));
  }
  on_ground_ = true;
  state_.p_WB.z() = rest_z_m;
  state_.v_W.setZero();
  state_.omega_B.setZero();
  // Upright on the gear: keep the heading of x_B, drop roll and pitch.
  const Eigen::Vector3d x_B_W = state_.q_WB * Eigen::Vector3d::UnitX();
  const double yaw = std::atan2(x_B_W.y(), x_B_W.x());
  state_.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

QuadrotorDynamics::Derivative QuadrotorDynamics::ComputeDerivative(
    const RigidBody& x, const Eigen::Vector4d& f_check_N) const {
  const Eigen::Matrix3d R_WB = RotationFromWxyz(x.q_wxyz);
  const Forces forces = ComputeForces(R_WB, x.v_W, x.omega_B, f_check_N);
  Derivative d;
  d.p_dot = x.v_W;  // (F.1)
  d.v_dot = R_WB * forces.specific_force_B -
            params_.vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ();  // (F.2)
  // (F.3) as q' = 1/2 q (x) (0, omega).
  const double w = x.q_wxyz[0];
  const Eigen::Vector3d q_vec = x.q_wxyz.tail<3>();
  d.q_dot[0] = -0.5 * q_vec.dot(x.omega_B);
  d.q_dot.tail<3>() = 0.5 * (w * x.omega_B + q_vec.cross(x.omega_B));
  d.omega_dot =
      inertia_inverse_ * (forces.torque_B - x.omega_B.cross(inertia_ * x.omega_B));  // (F.4)
  return d;
}

Eigen::Vector4d QuadrotorDynamics::RotorThrustsAfter(const Eigen::Vector4d& f_check_start,
                                                     double elapsed_s) const {
  const control::RotorParameters& rotor = params_.vehicle.rotor;
  Eigen::Vector4d f;
  for (int i = 0; i < 4; ++i) {
    const double target = TargetThrust(commands_[i]);
    // (G.7): the branch is fixed by the sign of (target - f) at the start of the interval, since
    // the exponential approach never crosses the target.
    const double tau =
        target >= f_check_start[i] ? rotor.time_constant_up_s : rotor.time_constant_down_s;
    f[i] = target + (f_check_start[i] - target) * std::exp(-elapsed_s / tau);
  }
  return f;
}

void QuadrotorDynamics::StepRk4(double h_s) {
  const RigidBody x0{
      state_.p_WB, state_.v_W,
      Eigen::Vector4d(state_.q_WB.w(), state_.q_WB.x(), state_.q_WB.y(), state_.q_WB.z()),
      state_.omega_B};
  const Eigen::Vector4d f_start = f_check_N_;
  const Eigen::Vector4d f_mid = RotorThrustsAfter(f_start, 0.5 * h_s);
  const Eigen::Vector4d f_end = RotorThrustsAfter(f_start, h_s);

  const auto advance = [&x0](const Derivative& d, double step) {
    return RigidBody{x0.p_W + step * d.p_dot, x0.v_W + step * d.v_dot, x0.q_wxyz + step * d.q_dot,
                     x0.omega_B + step * d.omega_dot};
  };
  const Derivative k1 = ComputeDerivative(x0, f_start);
  const Derivative k2 = ComputeDerivative(advance(k1, 0.5 * h_s), f_mid);
  const Derivative k3 = ComputeDerivative(advance(k2, 0.5 * h_s), f_mid);
  const Derivative k4 = ComputeDerivative(advance(k3, h_s), f_end);

  const double w = h_s / 6.0;
  state_.p_WB += w * (k1.p_dot + 2.0 * k2.p_dot + 2.0 * k3.p_dot + k4.p_dot);
  state_.v_W += w * (k1.v_dot + 2.0 * k2.v_dot + 2.0 * k3.v_dot + k4.v_dot);
  const Eigen::Vector4d q = x0.q_wxyz + w * (k1.q_dot + 2.0 * k2.q_dot + 2.0 * k3.q_dot + k4.q_dot);
  state_.q_WB = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  state_.omega_B += w * (k1.omega_dot + 2.0 * k2.omega_dot + 2.0 * k3.omega_dot + k4.omega_dot);
  f_check_N_ = f_end;
  state_.t_s += h_s;
}

void QuadrotorDynamics::Step(double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
    throw std::invalid_argument("QuadrotorDynamics::Step: dt_s must be finite and > 0, got " +
                                std::to_string(dt_s));
  }
  if (!(wind_W_.allFinite() && external_force_W_.allFinite() && external_torque_B_.allFinite())) {
    throw std::invalid_argument(
        "QuadrotorDynamics::Step: wind, external force and external torque must be finite");
  }
  // Tolerance keeps e.g. 0.001 / 0.001 from becoming 2 sub-steps through rounding.
  const int sub_steps =
      std::max(1, static_cast<int>(std::ceil(dt_s / params_.max_integration_step_s - 1e-9)));
  const double h_s = dt_s / sub_steps;
  for (int k = 0; k < sub_steps; ++k) {
    StepRk4(h_s);
    ResolveGroundContact();
  }
}

}  // namespace aperture::sim
