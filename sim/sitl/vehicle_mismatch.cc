#include "sim/sitl/vehicle_mismatch.h"

#include <cmath>
#include <random>
#include <string>

#include "control/require.h"

namespace aperture::sim {
namespace {

// Relative bounds draw factors 1 + U(-b, b), which must stay positive.
void RequireRelativeBound(double bound, const std::string& field) {
  control::Require(std::isfinite(bound) && bound >= 0.0 && bound < 1.0,
                   "VehicleMismatchBounds." + field, bound, "must be in [0, 1)");
}

void RequireLatencyRange(const Eigen::Vector2d& range_s, const std::string& field) {
  const std::string name = "VehicleMismatchBounds." + field;
  control::RequireNonNegative(range_s[0], name + "[0] (min)");
  control::RequireAtLeast(range_s[1], range_s[0], name + "[1] (max)");
  control::RequireFinite(range_s[1], name + "[1] (max)");
}

}  // namespace

void VehicleMismatchBounds::Validate() const {
  RequireRelativeBound(rotor_drag_relative, "rotor_drag_relative");
  control::RequireNonNegative(thrust_velocity_coeff_kh_max,
                              "VehicleMismatchBounds.thrust_velocity_coeff_kh_max");
  control::RequireNonNegative(quadratic_drag_max_per_m,
                              "VehicleMismatchBounds.quadratic_drag_max_per_m");
  control::RequireInRange(drag_thrust_exponent_max, 0.0, 2.0,
                          "VehicleMismatchBounds.drag_thrust_exponent_max");
  RequireRelativeBound(time_constant_relative, "time_constant_relative");
  RequireRelativeBound(thrust_map_relative, "thrust_map_relative");
  RequireRelativeBound(torque_map_relative, "torque_map_relative");
  RequireRelativeBound(rotor_fitness_relative, "rotor_fitness_relative");
  control::RequireNonNegative(battery_sag_max_per_s, "VehicleMismatchBounds.battery_sag_max_per_s");
  control::RequireNonNegative(esc_delay_max_s, "VehicleMismatchBounds.esc_delay_max_s");
  control::RequireNonNegative(gyro_vibration_noise_max,
                              "VehicleMismatchBounds.gyro_vibration_noise_max");
  RequireLatencyRange(command_latency_s, "command_latency_s");
  RequireLatencyRange(estimate_latency_s, "estimate_latency_s");
}

VehicleMismatch DrawVehicleMismatch(const VehicleMismatchBounds& bounds, std::uint64_t seed) {
  bounds.Validate();
  // A stream of its own: SitlRunnerParams::SetSeed derives the sensors' from the same seed.
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 0xD1B54A32D192ED03ull);
  const auto uniform = [&rng](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(rng);
  };
  const auto factor = [&uniform](double relative) { return 1.0 + uniform(-relative, relative); };
  VehicleMismatch m;
  m.rotor_drag_factor_xy.x() = factor(bounds.rotor_drag_relative);
  m.rotor_drag_factor_xy.y() = factor(bounds.rotor_drag_relative);
  m.thrust_velocity_coeff_kh = uniform(0.0, bounds.thrust_velocity_coeff_kh_max);
  m.quadratic_drag_per_m = uniform(0.0, bounds.quadratic_drag_max_per_m);
  m.drag_thrust_exponent = uniform(0.0, bounds.drag_thrust_exponent_max);
  m.time_constant_up_factor = factor(bounds.time_constant_relative);
  m.time_constant_down_factor = factor(bounds.time_constant_relative);
  m.thrust_map_factor = factor(bounds.thrust_map_relative);
  m.torque_map_factor = factor(bounds.torque_map_relative);
  for (int i = 0; i < 4; ++i) m.rotor_fitness_factor[i] = factor(bounds.rotor_fitness_relative);
  m.battery_sag_per_s = uniform(0.0, bounds.battery_sag_max_per_s);
  m.esc_delay_s = uniform(0.0, bounds.esc_delay_max_s);
  m.gyro_vibration_noise = uniform(0.0, bounds.gyro_vibration_noise_max);
  m.command_latency_s = uniform(bounds.command_latency_s[0], bounds.command_latency_s[1]);
  m.estimate_latency_s = uniform(bounds.estimate_latency_s[0], bounds.estimate_latency_s[1]);
  return m;
}

control::VehicleParameters MismatchedVehicle(const control::VehicleParameters& nominal,
                                             const VehicleMismatch& m) {
  control::VehicleParameters vehicle = nominal;
  vehicle.rotor_drag_D_per_s.head<2>() =
      vehicle.rotor_drag_D_per_s.head<2>().cwiseProduct(m.rotor_drag_factor_xy);
  vehicle.thrust_velocity_coeff_kh += m.thrust_velocity_coeff_kh;
  vehicle.rotor.time_constant_up_s *= m.time_constant_up_factor;
  vehicle.rotor.time_constant_down_s *= m.time_constant_down_factor;
  vehicle.rotor.thrust_coeffs_N *= m.thrust_map_factor;
  vehicle.rotor.torque_coeffs_Nm *= m.torque_map_factor;
  vehicle.rotor_fitness = vehicle.rotor_fitness.cwiseProduct(m.rotor_fitness_factor);
  return vehicle;
}

void ApplyVehicleMismatch(const VehicleMismatch& m, SitlRunnerParams* sitl) {
  if (!sitl->flight_controller_model) sitl->flight_controller_model = sitl->dynamics.vehicle;
  QuadrotorDynamicsParams& dynamics = sitl->dynamics;
  dynamics.vehicle = MismatchedVehicle(dynamics.vehicle, m);
  dynamics.quadratic_drag_per_m += m.quadratic_drag_per_m;
  dynamics.drag_thrust_exponent += m.drag_thrust_exponent;
  dynamics.battery_sag_per_s += m.battery_sag_per_s;
  sitl->esc_delay_s += m.esc_delay_s;
  sitl->command_latency_s += m.command_latency_s;
  sitl->estimate_latency_s += m.estimate_latency_s;
  sitl->imu.gyro_noise_density = std::hypot(sitl->imu.gyro_noise_density, m.gyro_vibration_noise);
}

double CalibrateHoverThrust(const VehicleMismatch& m, SitlRunnerParams* sitl) {
  control::Require(sitl->flight_controller_model.has_value(),
                   "CalibrateHoverThrust: SitlRunnerParams.flight_controller_model",
                   "must be set (call ApplyVehicleMismatch first)");
  const double lambda = m.thrust_map_factor * 4.0 / m.rotor_fitness_factor.cwiseInverse().sum();
  control::RotorParameters& rotor = sitl->flight_controller_model->rotor;
  rotor.thrust_coeffs_N *= lambda;
  rotor.torque_coeffs_Nm *= lambda;
  return lambda;
}

std::optional<VehicleMismatch> ApplyVehicleMismatch(const VehicleMismatchParams& params,
                                                    std::uint64_t seed, SitlRunnerParams* sitl) {
  if (!params.mismatch) return std::nullopt;
  const VehicleMismatch mismatch = DrawVehicleMismatch(params.mismatch_bounds, seed);
  ApplyVehicleMismatch(mismatch, sitl);
  if (params.hover_thrust_calibration) CalibrateHoverThrust(mismatch, sitl);
  return mismatch;
}

}  // namespace aperture::sim
