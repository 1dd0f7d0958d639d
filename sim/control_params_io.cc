#include "sim/control_params_io.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace aperture::sim {
namespace {

using Mixing = control::MixerParameters::Mixing;
using Saturation = control::MixerParameters::Saturation;
using BodyRateLaw = control::LowLevelControllerParameters::BodyRateLaw;

enum class BodyRatePreset { kLqr, kProportionalLowGain, kProportionalHighGain, kCustom };

BodyRatePreset PresetOf(const control::LowLevelControllerParameters& params) {
  if (params.body_rate_law == BodyRateLaw::kLqr) return BodyRatePreset::kLqr;
  const Eigen::Vector3d& gains = params.proportional.rate_gains_per_s;
  if (gains == control::ProportionalBodyRateParameters::LowGain().rate_gains_per_s) {
    return BodyRatePreset::kProportionalLowGain;
  }
  if (gains == control::ProportionalBodyRateParameters::HighGain().rate_gains_per_s) {
    return BodyRatePreset::kProportionalHighGain;
  }
  return BodyRatePreset::kCustom;
}

void LoadPositionGains(config::ParamReader& reader, control::PositionControllerParams* params) {
  reader.Read("p_xy_per_s2", &params->p_xy_per_s2);
  reader.Read("p_z_per_s2", &params->p_z_per_s2);
  reader.Read("d_xy_per_s", &params->d_xy_per_s);
  reader.Read("d_z_per_s", &params->d_z_per_s);
  reader.Read("p_rp_per_s", &params->attitude.p_rp_per_s);
  reader.Read("p_yaw_per_s", &params->attitude.p_yaw_per_s);
  reader.RejectUnknownKeys();
}

void LoadLqrWeights(config::ParamReader& reader, control::LqrBodyRateParameters* params) {
  reader.Read("state_weights", &params->state_weights);
  reader.Read("input_weights", &params->input_weights);
  reader.RejectUnknownKeys();
}

}  // namespace

void ControlStackParams::Validate() const {
  position.Validate();
  const auto& lqr = low_level.lqr;
  if (!lqr.state_weights.allFinite() || (lqr.state_weights.array() < 0.0).any()) {
    throw std::invalid_argument(
        "ControlStackParams.low_level.lqr.state_weights must be finite and non-negative");
  }
  if (!lqr.input_weights.allFinite() || (lqr.input_weights.array() <= 0.0).any()) {
    throw std::invalid_argument(
        "ControlStackParams.low_level.lqr.input_weights must be finite and positive (R > 0)");
  }
  const Eigen::Vector3d& gains = low_level.proportional.rate_gains_per_s;
  if (!gains.allFinite() || (gains.array() < 0.0).any()) {
    throw std::invalid_argument(
        "ControlStackParams.low_level.proportional.rate_gains_per_s must be finite and "
        "non-negative");
  }
  if (!std::isfinite(low_level.mixer.assured_yaw_torque_Nm) ||
      low_level.mixer.assured_yaw_torque_Nm < 0.0) {
    throw std::invalid_argument(
        "ControlStackParams.low_level.mixer.assured_yaw_torque_Nm must be finite and >= 0");
  }
}

std::string BodyRateName(const control::LowLevelControllerParameters& params) {
  switch (PresetOf(params)) {
    case BodyRatePreset::kLqr:
      return "lqr";
    case BodyRatePreset::kProportionalLowGain:
      return "p_low";
    case BodyRatePreset::kProportionalHighGain:
      return "p_high";
    case BodyRatePreset::kCustom:
      break;
  }
  return "p_custom";
}

const char* ToString(Mixing mixing) {
  return mixing == Mixing::kIterative ? "iterative" : "one_shot";
}

const char* ToString(Saturation saturation) {
  return saturation == Saturation::kPrioritized ? "prioritized" : "clipping";
}

void LoadParams(config::ParamReader& reader, ControlStackParams* params) {
  reader.Read("drag_compensation", &params->position.compensate_rotor_drag);
  BodyRatePreset preset = PresetOf(params->low_level);
  reader.ReadEnum("body_rate", &preset,
                  {{"lqr", BodyRatePreset::kLqr},
                   {"p_low", BodyRatePreset::kProportionalLowGain},
                   {"p_high", BodyRatePreset::kProportionalHighGain}});
  switch (preset) {
    case BodyRatePreset::kLqr:
      params->low_level.body_rate_law = BodyRateLaw::kLqr;
      break;
    case BodyRatePreset::kProportionalLowGain:
      params->low_level.body_rate_law = BodyRateLaw::kProportional;
      params->low_level.proportional = control::ProportionalBodyRateParameters::LowGain();
      break;
    case BodyRatePreset::kProportionalHighGain:
      params->low_level.body_rate_law = BodyRateLaw::kProportional;
      params->low_level.proportional = control::ProportionalBodyRateParameters::HighGain();
      break;
    case BodyRatePreset::kCustom:  // only reachable as the unchanged default
      break;
  }
  reader.ReadEnum("mixer", &params->low_level.mixer.mixing,
                  {{"iterative", Mixing::kIterative}, {"one_shot", Mixing::kOneShot}});
  reader.ReadEnum("saturation", &params->low_level.mixer.saturation,
                  {{"prioritized", Saturation::kPrioritized}, {"clipping", Saturation::kClip}});
  reader.Read("assured_yaw_torque_Nm", &params->low_level.mixer.assured_yaw_torque_Nm);
  config::ParamReader position = reader.Section("position");
  LoadPositionGains(position, &params->position);
  config::ParamReader lqr = reader.Section("lqr");
  LoadLqrWeights(lqr, &params->low_level.lqr);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::sim
