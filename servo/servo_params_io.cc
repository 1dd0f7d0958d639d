#include "servo/servo_params_io.h"

namespace aperture::servo {

void LoadParams(config::ParamReader& reader, ServoGain* params) {
  reader.Read("at_zero_per_s", &params->at_zero_per_s);
  reader.Read("at_infinity_per_s", &params->at_infinity_per_s);
  reader.Read("slope_at_zero_per_s", &params->slope_at_zero_per_s);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, MomentServoParams* params) {
  reader.ReadEnum("yaw", &params->yaw,
                  {{"hold", YawMode::kHold}, {"orientation", YawMode::kOrientation}});
  reader.Read("min_area_n2", &params->min_area_n2);
  reader.Read("min_orientation_anisotropy", &params->min_orientation_anisotropy);
  reader.ReadSection("gain", &params->gain);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, PidServoParams* params) {
  reader.Read("kp_mps", &params->kp_mps);
  reader.Read("ki_mps2", &params->ki_mps2);
  reader.Read("kd_m", &params->kd_m);
  reader.Read("max_speed_mps", &params->max_speed_mps);
  reader.Read("forward_pitch_deg", &params->forward_pitch_deg);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, PointServoParams* params) {
  reader.ReadSection("gain", &params->gain);
  reader.Read("compensate_target_motion", &params->compensate_target_motion);
  reader.Read("target_motion_time_constant_s", &params->target_motion_time_constant_s);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, GapServoParams* params) {
  reader.ReadEnum("law", &params->law,
                  {{"moments", GapServoLaw::kMoments}, {"pid", GapServoLaw::kPid}});
  reader.ReadSection("moments", &params->moments);
  reader.ReadSection("pid", &params->pid);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::servo
