#pragma once
// YAML loaders (config::ParamReader, STYLE.md 6) for the servo laws' parameters. Keys are the
// field names (they carry their units); absent keys keep the in-class defaults; unknown keys are
// rejected with their location and the known keys; each loaded struct is validated.
//
//   servo:                          # GapServoParams (`--set servo.law=pid`)
//     law: moments                  # moments | pid
//     moments:                      # MomentServoParams
//       yaw: hold                   # hold | orientation
//       min_area_n2: 1.0e-6
//       min_orientation_anisotropy: 0.01
//       gain: {at_zero_per_s: 1.5, at_infinity_per_s: 0.7, slope_at_zero_per_s: 30}
//     pid:                          # PidServoParams (GapFlyt Sec. III-B)
//       kp_mps: 2.5
//       ki_mps2: 0.5
//       kd_m: 0.2
//       max_speed_mps: 1.0
//       forward_pitch_deg: 3.0
//   tag_servo:                      # PointServoParams
//     gain: {at_zero_per_s: 1.5, at_infinity_per_s: 0.7, slope_at_zero_per_s: 30}
//     compensate_target_motion: true
//     target_motion_time_constant_s: 0.2
//
// All throw std::invalid_argument naming where the bad value is and what is expected.
#include "config/param_reader.h"
#include "servo/gap_servo.h"
#include "servo/moment_servo.h"
#include "servo/pid_servo.h"
#include "servo/point_servo.h"
#include "servo/servo_gain.h"

namespace aperture::servo {

void LoadParams(config::ParamReader& reader, ServoGain* params);
void LoadParams(config::ParamReader& reader, MomentServoParams* params);
void LoadParams(config::ParamReader& reader, PidServoParams* params);
void LoadParams(config::ParamReader& reader, PointServoParams* params);
void LoadParams(config::ParamReader& reader, GapServoParams* params);

}  // namespace aperture::servo
