#pragma once
// The control stack of one SITL flight as configuration (issue 4): the high-level position
// controller (Faessler thesis F.31-F.38, attitude law of paper B) that an autopilot runs, and the
// flight controller's body-rate law, mixer and saturation (App. G). control/ is Eigen-only, so the
// YAML loader (config::ParamReader, STYLE.md 6) lives here beside sim_params_io.h.
//
//   control:
//     drag_compensation: true      # F.7.4: false = "not considering drag" (D = 0, k_h = 0)
//     body_rate: lqr               # lqr (G.12) | p_low | p_high (P law B.21, Table G.1 (a), (b))
//     mixer: iterative             # iterative (G.4) | one_shot (Table G.2 baseline)
//     saturation: prioritized      # prioritized (Algorithm 4) | clipping
//     assured_yaw_torque_Nm: 0.0   # eta_z,assured of Algorithm 4 (0: off)
//     position: {p_xy_per_s2: 5, p_z_per_s2: 15, d_xy_per_s: 4, d_z_per_s: 6,
//                p_rp_per_s: 16.6, p_yaw_per_s: 5}          # Table A.2
//     lqr: {state_weights: [0.01, 0.01, 0.0016, 0, 0, 0], input_weights: [1, 1, 1]}  # (G.10)
//
// Absent keys keep the in-class defaults; unknown keys and enum values name the key and list what
// is allowed; the loader ends with ControlStackParams::Validate().
#include <string>

#include "config/param_reader.h"
#include "control/low_level_controller.h"
#include "control/position_controller.h"

namespace aperture::sim {

struct ControlStackParams {
  // Autopilot side: gains and the drag switch (compensate_rotor_drag, key drag_compensation).
  control::PositionControllerParams position;
  // Flight-controller side: body-rate law (+ P gains or LQR weights), mixer, saturation.
  control::LowLevelControllerParameters low_level;
  // Throws std::invalid_argument naming the field for negative / non-finite gains or weights and
  // non-positive LQR input weights.
  void Validate() const;
};

// "lqr", "p_low", "p_high" (the presets of ProportionalBodyRateParameters), or "p_custom" for
// other proportional gains.
std::string BodyRateName(const control::LowLevelControllerParameters& params);
const char* ToString(control::MixerParameters::Mixing mixing);          // "iterative", "one_shot"
const char* ToString(control::MixerParameters::Saturation saturation);  // "prioritized", "clipping"

void LoadParams(config::ParamReader& reader, ControlStackParams* params);

}  // namespace aperture::sim
