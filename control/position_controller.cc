#include "control/position_controller.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
namespace {

VehicleParameters ControllerModel(const VehicleParameters& vehicle,
                                  const PositionControllerParams& params) {
  vehicle.Validate();
  params.Validate();
  VehicleParameters model = vehicle;
  if (!params.compensate_rotor_drag) {
    model.rotor_drag_D_per_s.setZero();
    model.thrust_velocity_coeff_kh = 0.0;
  }
  return model;
}

}  // namespace

void PositionControllerParams::Validate() const {
  RequireNonNegative(p_xy_per_s2, "PositionControllerParams.p_xy_per_s2");
  RequireNonNegative(p_z_per_s2, "PositionControllerParams.p_z_per_s2");
  RequireNonNegative(d_xy_per_s, "PositionControllerParams.d_xy_per_s");
  RequireNonNegative(d_z_per_s, "PositionControllerParams.d_z_per_s");
  attitude.Validate();
}

PositionController::PositionController(const VehicleParameters& vehicle,
                                       const PositionControllerParams& params)
    : params_(params),
      model_(ControllerModel(vehicle, params)),
      attitude_controller_(params.attitude) {}

PositionControllerOutput PositionController::Compute(const QuadState& state,
                                                     const TrajectoryPoint& reference) const {
  if (!state.IsValid()) {
    throw std::invalid_argument(
        "PositionController::Compute: state at t = " + std::to_string(state.t_s) +
        " s is not finite or q_WB is not a unit quaternion; check the "
        "state estimator output");
  }
  PositionControllerOutput out;
  out.reference = ComputeFlatnessOutputs(reference, model_);
  const Eigen::Matrix3d& R_ref = out.reference.R_WB;

  // (F.31), (F.32); a_rd = -R_ref D R_ref^T v_ref.
  const Eigen::Vector3d p_error = state.p_WB - reference.p_W;
  const Eigen::Vector3d v_error = state.v_W - reference.v_W;
  const Eigen::Vector3d a_fb(-params_.p_xy_per_s2 * p_error.x() - params_.d_xy_per_s * v_error.x(),
                             -params_.p_xy_per_s2 * p_error.y() - params_.d_xy_per_s * v_error.y(),
                             -params_.p_z_per_s2 * p_error.z() - params_.d_z_per_s * v_error.z());
  const Eigen::Vector3d a_rd =
      -R_ref * (model_.rotor_drag_D_per_s.asDiagonal() * (R_ref.transpose() * reference.v_W));
  out.a_des_W = a_fb + reference.a_W - a_rd + model_.gravity_mps2 * Eigen::Vector3d::UnitZ();

  const Eigen::Matrix3d R = state.q_WB.toRotationMatrix();
  const double a_des_norm = out.a_des_W.norm();
  out.thrust_direction_defined = a_des_norm >= kMinThrust_mps2;
  const Eigen::Vector3d z_des = out.thrust_direction_defined
                                    ? Eigen::Vector3d(out.a_des_W / a_des_norm)
                                    : R.col(2);  // (F.33)
  out.attitude = attitude_controller_.Compute(state.q_WB, z_des, reference.heading_rad);

  // (F.36) with the current body axes and velocity.
  const double v_h = state.v_W.dot(R.col(0) + R.col(1));
  out.command.collective_thrust_mps2 =
      out.a_des_W.dot(R.col(2)) - model_.thrust_velocity_coeff_kh * v_h * v_h;
  if (params_.compensate_rotor_lag) {
    const double c_dot = out.reference.collective_thrust_rate_mps3;
    const double tau_s =
        c_dot > 0.0 ? model_.rotor.time_constant_up_s : model_.rotor.time_constant_down_s;
    out.command.collective_thrust_mps2 += tau_s * c_dot;
  }
  out.command.omega_des_B = out.attitude.omega_fb_B + out.reference.omega_B;  // (F.37)
  out.command.omega_dot_des_B = out.reference.omega_dot_B;                    // (F.38)
  return out;
}

}  // namespace aperture::control
