#include "sim/sim_params_io.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace aperture::sim {
namespace {

// Seeds are 64-bit in the structs but YAML integers are read as int; negative seeds are refused.
void ReadSeed(config::ParamReader& reader, std::uint64_t* seed) {
  if (!reader.Has("seed")) return;
  int value = 0;
  reader.Read("seed", &value);
  if (value < 0) {
    throw std::invalid_argument(reader.Where("seed") + ": key '" + reader.FullKey("seed") +
                                "' expects a non-negative integer, got " + std::to_string(value));
  }
  *seed = static_cast<std::uint64_t>(value);
}


void LoadRotorParameters(config::ParamReader& reader, control::RotorParameters* params) {
  reader.Read("thrust_coeffs_N", &params->thrust_coeffs_N);
  reader.Read("torque_coeffs_Nm", &params->torque_coeffs_Nm);
  reader.Read("time_constant_up_s", &params->time_constant_up_s);
  reader.Read("time_constant_down_s", &params->time_constant_down_s);
  reader.Read("command_min", &params->command_min);
  reader.Read("command_max", &params->command_max);
  reader.RejectUnknownKeys();
}

}  // namespace

void LoadVehicleParameters(config::ParamReader& reader, control::VehicleParameters* params) {
  reader.Read("mass_kg", &params->mass_kg);
  reader.Read("inertia_diag_kgm2", &params->inertia_diag_kgm2);
  reader.Read("arm_length_m", &params->arm_length_m);
  reader.Read("gravity_mps2", &params->gravity_mps2);
  reader.Read("rotor_drag_D_per_s", &params->rotor_drag_D_per_s);
  reader.Read("rotor_drag_A", &params->rotor_drag_A);
  reader.Read("rotor_drag_B", &params->rotor_drag_B);
  reader.Read("thrust_velocity_coeff_kh", &params->thrust_velocity_coeff_kh);
  reader.Read("rotor_fitness", &params->rotor_fitness);
  config::ParamReader rotor = reader.Section("rotor");
  LoadRotorParameters(rotor, &params->rotor);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, QuadrotorDynamicsParams* params) {
  config::ParamReader vehicle = reader.Section("vehicle");
  LoadVehicleParameters(vehicle, &params->vehicle);
  reader.Read("max_integration_step_s", &params->max_integration_step_s);
  reader.Read("rotor_lag_enabled", &params->rotor_lag_enabled);
  reader.Read("ground_contact_enabled", &params->ground_contact_enabled);
  reader.Read("ground_height_m", &params->ground_height_m);
  reader.Read("landing_gear_height_m", &params->landing_gear_height_m);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, DisturbanceParams* params) {
  reader.Read("steady_wind_W_mps", &params->steady_wind_W_mps);
  if (reader.Has("gusts")) {
    std::vector<Eigen::Matrix<double, 5, 1>> rows;
    reader.Read("gusts", &rows);
    params->gusts.clear();
    for (const auto& row : rows) params->gusts.push_back({row[0], row[1], row.tail<3>()});
  }
  if (reader.Has("pushes")) {
    std::vector<Eigen::VectorXd> rows;
    reader.Read("pushes", &rows);
    params->pushes.clear();
    for (size_t i = 0; i < rows.size(); ++i) {
      const Eigen::VectorXd& row = rows[i];
      if (row.size() != 4 && row.size() != 7) {
        throw std::invalid_argument(reader.Where("pushes") + ": key '" + reader.FullKey("pushes") +
                                    "[" + std::to_string(i) + "]' expects [t_s, J_x, J_y, J_z] or " +
                                    "[t_s, J_x, J_y, J_z, L_x, L_y, L_z], got " +
                                    std::to_string(row.size()) + " numbers");
      }
      Push push{row[0], row.segment<3>(1), Eigen::Vector3d::Zero()};
      if (row.size() == 7) push.angular_impulse_B_Nms = row.tail<3>();
      params->pushes.push_back(push);
    }
  }
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, OdometrySensorParams* params) {
  reader.Read("rate_hz", &params->rate_hz);
  reader.Read("position_sigma_m", &params->position_sigma_m);
  reader.Read("rotation_sigma_rad", &params->rotation_sigma_rad);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, ImuSensorParams* params) {
  reader.Read("rate_hz", &params->rate_hz);
  reader.Read("latency_s", &params->latency_s);
  reader.Read("stamp_at_delivery", &params->stamp_at_delivery);
  reader.Read("accel_noise_density", &params->accel_noise_density);
  reader.Read("gyro_noise_density", &params->gyro_noise_density);
  reader.Read("accel_bias_random_walk", &params->accel_bias_random_walk);
  reader.Read("gyro_bias_random_walk", &params->gyro_bias_random_walk);
  reader.Read("accel_bias_initial_B", &params->accel_bias_initial_B);
  reader.Read("gyro_bias_initial_B", &params->gyro_bias_initial_B);
  ReadSeed(reader, &params->seed);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, RangeSensorParams* params) {
  reader.Read("rate_hz", &params->rate_hz);
  reader.Read("min_range_m", &params->min_range_m);
  reader.Read("max_range_m", &params->max_range_m);
  reader.Read("noise_sigma_m", &params->noise_sigma_m);
  reader.Read("max_tilt_rad", &params->max_tilt_rad);
  reader.Read("p_BS", &params->p_BS);
  ReadSeed(reader, &params->seed);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, CollisionParams* params) {
  reader.Read("body_radius_m", &params->body_radius_m);
  reader.Read("propeller_radius_m", &params->propeller_radius_m);
  reader.Read("ground_enabled", &params->ground_enabled);
  reader.Read("max_touchdown_speed_mps", &params->max_touchdown_speed_mps);
  reader.Read("max_touchdown_tilt_rad", &params->max_touchdown_tilt_rad);
  reader.Read("ignored_objects", &params->ignored_objects);
  reader.Read("sphere_rays", &params->sphere_rays);
  reader.Read("disk_rays", &params->disk_rays);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, SitlRunnerParams* params) {
  reader.Read("dynamics_rate_hz", &params->dynamics_rate_hz);
  reader.Read("control_rate_hz", &params->control_rate_hz);
  reader.Read("command_latency_s", &params->command_latency_s);
  reader.Read("range_latency_s", &params->range_latency_s);
  reader.Read("range_enabled", &params->range_enabled);
  reader.Read("start_hovering", &params->start_hovering);
  reader.RejectUnknownKeys();
  // No Validate() here: the rate checks compare against the IMU, range and flight-controller
  // rates, which other sections set; SitlRunner validates the assembled struct.
}

}  // namespace aperture::sim
