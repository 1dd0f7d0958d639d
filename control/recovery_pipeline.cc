#include "control/recovery_pipeline.h"

namespace aperture::control {

RecoveryPipeline::RecoveryPipeline(const VehicleParameters& vehicle,
                                   const RecoveryPipelineParams& params)
    : params_(params),
      launch_(params.launch ? *params.launch : LaunchDetectorParams::FromVehicle(vehicle)),
      attitude_(params.attitude),
      height_(params.height),
      machine_(vehicle, params.recovery) {}

void RecoveryPipeline::AddImu(double t_s, const Eigen::Vector3d& specific_force_B,
                              const Eigen::Vector3d& omega_B) {
  attitude_.AddImu(t_s, specific_force_B, omega_B);  // validates t_s and the sample
  launch_.AddSample(t_s, specific_force_B);
  if (height_.initialized() && has_imu_time_) {
    height_.Predict(t_s - last_imu_t_s_,
                    HeightFilter::VerticalAcceleration(
                        attitude_.q_WB(), specific_force_B - params_.attitude.accel_bias_B,
                        params_.height.gravity_mps2));
  }
  has_imu_time_ = true;
  last_imu_t_s_ = t_s;
}

void RecoveryPipeline::AddRange(double range_m) {
  if (!height_filter_requested_ && !height_.initialized()) return;
  const std::optional<double> z_m = HeightFilter::HeightFromRange(range_m, attitude_.q_WB());
  if (!z_m) return;
  if (height_filter_requested_) {
    height_.Initialize(*z_m);
    height_filter_requested_ = false;
  } else {
    height_.Update(*z_m);
  }
}

RecoveryOutput RecoveryPipeline::Step(double t_s) {
  RecoveryInputs in;
  in.t_s = t_s;
  in.launch_detected = launch_.launched();
  in.q_WB = attitude_.q_WB();
  in.omega_B = attitude_.omega_B();
  if (height_.initialized()) in.height = height_.estimate();
  in.vision_state = vision_state_;
  const RecoveryOutput out = machine_.Step(in);
  if (out.initialize_height_filter) height_filter_requested_ = true;
  return out;
}

void RecoveryPipeline::Restart(double t_s) {
  machine_.StartWithoutLaunch(t_s);
  height_ = HeightFilter(params_.height);
  vision_state_.reset();
  height_filter_requested_ = false;
}

}  // namespace aperture::control
