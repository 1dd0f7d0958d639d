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

}  // namespace

void ControlStackParams::Validate() const {
  position.Validate();
  low_level.Validate();
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

void ApplyPreset(BodyRatePreset preset, control::LowLevelControllerParameters* params) {
  switch (preset) {
    case BodyRatePreset::kLqr:
      params->body_rate_law = BodyRateLaw::kLqr;
      return;
    case BodyRatePreset::kProportionalLowGain:
      params->body_rate_law = BodyRateLaw::kProportional;
      params->proportional = control::ProportionalBodyRateParameters::LowGain();
      return;
    case BodyRatePreset::kProportionalHighGain:
      params->body_rate_law = BodyRateLaw::kProportional;
      params->proportional = control::ProportionalBodyRateParameters::HighGain();
      return;
    case BodyRatePreset::kCustom:
      params->body_rate_law = BodyRateLaw::kProportional;
      return;
  }
}

const config::EnumNames<BodyRatePreset>& BodyRatePresetNames() {
  static const config::EnumNames<BodyRatePreset> kNames = {
      {"lqr", BodyRatePreset::kLqr},
      {"p_low", BodyRatePreset::kProportionalLowGain},
      {"p_high", BodyRatePreset::kProportionalHighGain},
      {"p_custom", BodyRatePreset::kCustom}};
  return kNames;
}

const config::EnumNames<Mixing>& MixingNames() {
  static const config::EnumNames<Mixing> kNames = {{"iterative", Mixing::kIterative},
                                                   {"one_shot", Mixing::kOneShot}};
  return kNames;
}

const config::EnumNames<Saturation>& SaturationNames() {
  static const config::EnumNames<Saturation> kNames = {{"prioritized", Saturation::kPrioritized},
                                                       {"clipping", Saturation::kClip}};
  return kNames;
}

}  // namespace aperture::sim
