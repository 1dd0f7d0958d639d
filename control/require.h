#pragma once
// Checks of bad input or configuration (STYLE.md 7, first tier), the one home for them. Each throws
// std::invalid_argument with one message shape that names the value and what it must be:
//   "<name> = <value> <rule>"   e.g. "GapMissionParams.hover_s = -1 must be finite and >= 0"
// `name` is the full name the user can find (struct and field, "SitlRunnerParams.dt_s"), so the
// message says what to fix. Values print with 6 significant digits (nan, inf as such).
#include <Eigen/Core>
#include <string>

namespace aperture::control {

// The general form: throws "<name> = <value> <rule>" when !ok.
void Require(bool ok, const std::string& name, double value, const std::string& rule);
// For conditions without one value: throws "<name> <rule>" when !ok.
void Require(bool ok, const std::string& name, const std::string& rule);

void RequireFinite(double value, const std::string& name);       // not NaN or inf
void RequirePositive(double value, const std::string& name);     // finite and > 0
void RequireNonNegative(double value, const std::string& name);  // finite and >= 0
void RequireAtLeast(double value, double minimum, const std::string& name);
void RequireInRange(double value, double minimum, double maximum,
                    const std::string& name);  // finite, in [minimum, maximum]

// Every entry finite: throws "<name> must be finite (no NaN or inf entries)".
template <typename Derived>
void RequireFinite(const Eigen::DenseBase<Derived>& value, const std::string& name) {
  Require(value.allFinite(), name, "must be finite (no NaN or inf entries)");
}

}  // namespace aperture::control
