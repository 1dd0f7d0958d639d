#pragma once
// The control stack of one SITL flight as configuration (issue 4): the high-level position
// controller (Faessler thesis F.31-F.38, attitude law of paper B) that an autopilot runs, and the
// flight controller's body-rate law, mixer and saturation (App. G). Described once by Serialize
// (config/param_archive.h): LoadParams(reader, &params) loads, config::DumpParams dumps.
//
//   control:
//     drag_compensation: true      # F.7.4: false = "not considering drag" (D = 0, k_h = 0)
//     body_rate: lqr               # lqr (G.12) | p_low | p_high (P law B.21, Table G.1 (a), (b))
//                                  # | p_custom with p_rate_gains_per_s: [k_p, k_q, k_r]
//     mixer: iterative             # iterative (G.4) | one_shot (Table G.2 baseline)
//     saturation: prioritized      # prioritized (Algorithm 4) | clipping
//     assured_yaw_torque_Nm: 0.0   # eta_z,assured of Algorithm 4 (0: off)
//     torque_observer_time_constant_s: 0  # beyond the thesis: torque-disturbance observer (0: off)
//     position: {p_xy_per_s2: 5, p_z_per_s2: 15, d_xy_per_s: 4, d_z_per_s: 6,
//                p_rp_per_s: 16.6, p_yaw_per_s: 5}          # Table A.2
//     lqr: {state_weights: [0.01, 0.01, 0.0016, 0, 0, 0], input_weights: [1, 1, 1]}  # (G.10)
//
// Absent keys keep the in-class defaults; unknown keys and enum values name the key and list what
// is allowed; the loader ends with ControlStackParams::Validate().
#include <string>

#include "config/yaml_read_archive.h"
#include "control/control_params_io.h"
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

// The body-rate law as one name: a preset of ProportionalBodyRateParameters or custom P gains.
enum class BodyRatePreset { kLqr, kProportionalLowGain, kProportionalHighGain, kCustom };
BodyRatePreset PresetOf(const control::LowLevelControllerParameters& params);
// Sets the law (and for p_low / p_high the gains) of a preset; kCustom: the P law, gains kept.
void ApplyPreset(BodyRatePreset preset, control::LowLevelControllerParameters* params);
const config::EnumNames<BodyRatePreset>& BodyRatePresetNames();
const config::EnumNames<control::MixerParameters::Mixing>& MixingNames();
const config::EnumNames<control::MixerParameters::Saturation>& SaturationNames();

template <typename Archive>
void Serialize(Archive* a, ControlStackParams* p) {
  a->Visit("drag_compensation", &p->position.compensate_rotor_drag);
  // The law is a name; custom P gains (p_custom) are the only gains written beside it, so a
  // `--set control.body_rate=p_high` over a dumped configuration is not undone by stale gains.
  BodyRatePreset preset = PresetOf(p->low_level);
  a->Visit("body_rate", &preset, BodyRatePresetNames());
  if constexpr (Archive::kLoading) ApplyPreset(preset, &p->low_level);
  if (preset == BodyRatePreset::kCustom) {
    a->Visit("p_rate_gains_per_s", &p->low_level.proportional.rate_gains_per_s);
  }
  a->Visit("mixer", &p->low_level.mixer.mixing, MixingNames());
  a->Visit("saturation", &p->low_level.mixer.saturation, SaturationNames());
  a->Visit("assured_yaw_torque_Nm", &p->low_level.mixer.assured_yaw_torque_Nm);
  a->Visit("torque_observer_time_constant_s", &p->low_level.torque_observer_time_constant_s);
  a->VisitSection("position",
                  [p](auto* section) { control::SerializePositionGains(section, &p->position); });
  a->Visit("lqr", &p->low_level.lqr);
}

}  // namespace aperture::sim
